"""The README's `drape` commands, walked as written from a folder outside the checkout (issue 57): every line
of the block under "The `drape` program" is either run here, in order, with `build/bin/drape` standing for the
built program, or named below with the reason it is not (a placeholder to fill in, an input an earlier
unrun command makes, or minutes of work). A new line in that block fails this test until it is classified,
so the README cannot drift from what works."""
import re
import shlex
import subprocess

from conftest import DRAPE, SOURCE

# Lines run as written, by their first words (after `build/bin/drape`).
RUN = [
    "--help",
    "body --bmi 38",
    "body --param rig=human",
    "body --sample 8",
    "body --bmi 30 --pose",
    "body --unpose posed.obj",
    "predict --bmi 35",
    "predict --bmi 30 --pose",
    "render --bmi 35",
    "model set models/tshirt-coarse.h5",
    "bench list",
]

# Lines not run, and why.
NOT_RUN = {
    "plugins [": "a usage line: [--kind K] [--brief] are placeholders",
    "graph check FILE": "a usage line: FILE is a placeholder",
    "assets [": "a usage line: its options are in brackets",
    "body --model smpl": "needs smpl.h5, a licensed SMPL model the user converts (tests/smpl poses a synthetic one by a theta file)",
    "spectral --mesh garment.obj": "needs shape.obj, a drape of the user's",
    "hierarchy --mesh garment.obj": "needs garment.obj from simulate or predict, further down",
    "simulate graphs/scenes/tshirt.yaml": "a default-resolution drape: minutes (tests/cli simulates scenes)",
    "simulate graphs/scenes/tshirt_coarse_friction.yaml": "a BMI 55 drape: minutes (tests/cli simulates scenes)",
    "simulate graphs/scenes/tshirt_coarse_posed.yaml": "a posed drape: half a minute (tests/physics drapes posed bodies)",
    "generate ": "2,000 drapes: hours (tests/cli generates small datasets)",
    "dataset unpose posed.h5": "needs posed.h5 from generate --poses draw",
    "dataset resample": "half a minute over the human rig's shards; tests/python/test_dataset_resample.py runs it on shard 0",
    "dataset merge": "needs shard0.h5 and shard1.h5 from generate --shard",
    "dataset info all.h5": "needs all.h5 from dataset merge",
    "dataset slim all.h5": "needs all.h5 from dataset merge",
    "dataset potential all.h5": "needs all.h5 from dataset merge",
    "train graphs/human": "trains on 500-odd drapes for minutes; tests/python/test_encoder_body.py trains its graph for an epoch",
    "train ": "needs data.h5 from generate; 100 epochs",
    "predict --body scan.obj": "needs scan.obj, a user's body mesh (tests/cli/body_heading_cli_test.cpp and "
    "posed_mesh_cli_test.cpp turn, move and pose bodies for it)",
    "model info model.h5": "needs model.h5 from train",
    "eval ": "needs model.h5 and data.h5",
    "optimize --scene graphs/scenes/tshirt_coarse_contact.yaml --bmi 35": "100 Adam iterations through the potential: a minute",
    "optimize --model models/tshirt-coarse.h5 --scene graphs/scenes/tshirt_coarse_sized.yaml --data": "needs data.h5",
    "experiment ": "trains and evaluates models: hours",
}


def readme_drape_lines():
    text = (SOURCE / "README.md").read_text()
    block = re.search(r"## The `drape` program\n\n```sh\n(.*?)\n```", text, re.S)
    assert block, "README.md has no ```sh block under '## The `drape` program'"
    lines = []
    for line in block.group(1).splitlines():
        command = re.split(r"\s+#", line)[0].strip()
        if command:
            lines.append(command)
    return lines


def classify(command):
    words = command.split()
    if words[0] == "mpirun":
        return None, "mpirun: needs data.h5 and MPI ranks"
    assert words[0] == "build/bin/drape", f"README line does not start with build/bin/drape: {command}"
    rest = command[len("build/bin/drape "):]
    run = [r for r in RUN if rest.startswith(r)]
    skip = [why for prefix, why in NOT_RUN.items() if rest.startswith(prefix)]
    return (rest if run else None), (skip[0] if skip else None)


def test_every_readme_command_is_run_or_says_why_not(tmp_path):
    ran = []
    for command in readme_drape_lines():
        rest, why = classify(command)
        assert rest or why, f"README line neither run nor explained in {__file__}: {command}"
        if not rest:
            continue
        p = subprocess.run([str(DRAPE), *shlex.split(rest)], cwd=tmp_path, capture_output=True, text=True,
                           timeout=300)
        assert p.returncode == 0, f"README command failed from {tmp_path}: {command}\n{p.stdout}\n{p.stderr}"
        ran.append(rest)
    assert len(ran) == len(RUN), f"some commands this test runs are no longer in the README: {RUN} vs {ran}"
    # What they wrote is where the README says, in the folder they ran from.
    for out in ["body.obj", "bodies.svg", "posed.obj", "garment.obj", "shirt.obj", "drape.html", "no_untangle.h5"]:
        assert (tmp_path / out).stat().st_size > 0, out
