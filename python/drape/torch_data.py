"""drape datasets as PyTorch datasets (docs/python.md, "Datasets in PyTorch").

    import torch, drape.torch_data
    data = drape.torch_data.DrapeDataset("datasets/bodyspace2000-friction/shard-*-of-40.h5", split="train")
    loader = torch.utils.data.DataLoader(data, batch_size=16, shuffle=True)
    for batch in loader:
        batch["body"]      # float32 [16, Nb, 3], metres
        batch["garment"]   # float32 [16, Ng, 3]

A sample is a dict of tensors:
    body         float32 [Nb, 3]  the body's vertices (a slim file's rebuilt from its shape parameters, once each)
    garment      float32 [Ng, 3]  the simulated drape
    body_params  float32 [P]      the body model's shape parameters
    split        int64 []         0 train, 1 val, 2 test
    index        int64 []         the sample's row in the dataset (over all the pattern's files)
    pose         float32 [A]      in a posed dataset only: the joint angles in degrees, in the order of
                                  drape.Dataset(path).layout["pose_angles"] (the body is posed in them)
With posing=True, also what a model of posed drapes reads (docs/poses.md, drape.Dataset.posing):
    unposed      float32 [Nb, 3]  the body at rest
    transforms   float32 [J, 12]  each joint's rigid transform into the pose (R row by row, then t)
    angles       float32 [A]      the pose's angles in radians (an A-pose dataset: each body's rest angles)
DataLoader's default collate stacks them into a batch. `faces` (int64 [F, 3], or None for files written before
datasets carried them) is the garment template's triangles. The drape file is opened once per process, so the
dataset goes to DataLoader workers (fork or spawn) as its path and split.
"""
import os

import torch

import drape

__all__ = ["DrapeDataset"]


class DrapeDataset(torch.utils.data.Dataset):
    """The done samples of a drape dataset (a file, a glob pattern of shards, slim or whole) in one split
    ('train', 'val', 'test', 'train,val' or 'all'), in file order. transform, when given, maps each sample
    dict to whatever the loader should get."""

    def __init__(self, path, split="all", transform=None, posing=False):
        self.path = os.fspath(path)
        self.split = split
        self.transform = transform
        self.posing = posing
        reader = self._reader()
        self.indices = reader.indices(split)
        faces = reader.faces
        self.faces = None if faces is None else torch.from_numpy(faces.astype("int64"))
        self.files = reader.files

    def _reader(self):
        # One reader per process: an HDF5 file handle must not cross a fork into DataLoader workers.
        if getattr(self, "_pid", None) != os.getpid():
            self._native, self._pid = drape.Dataset(self.path), os.getpid()
        return self._native

    def __getstate__(self):
        state = dict(self.__dict__)
        state.pop("_native", None)
        state.pop("_pid", None)
        return state

    def __len__(self):
        return len(self.indices)

    def __getitem__(self, i):
        row = int(self.indices[i])  # IndexError past the end, as a sequence
        batch = self._reader().read([row])
        sample = {
            "body": torch.from_numpy(batch["body"][0]),
            "garment": torch.from_numpy(batch["garment"][0]),
            "body_params": torch.from_numpy(batch["body_params"][0]),
            "split": torch.tensor(int(batch["split"][0]), dtype=torch.int64),
            "index": torch.tensor(row, dtype=torch.int64),
        }
        if "pose" in batch:
            sample["pose"] = torch.from_numpy(batch["pose"][0])
        if self.posing:
            p = self._reader().posing([row])
            for key in ("unposed", "transforms", "angles"):
                sample[key] = torch.from_numpy(p[key][0])
        return self.transform(sample) if self.transform else sample

    def __repr__(self):
        return f"<drape.torch_data.DrapeDataset {self.path} ({self.split}): {len(self)} samples>"
