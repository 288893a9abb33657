#!/usr/bin/env python3
"""drape from Python and PyTorch, end to end (docs/python.md):

  1. a body of the requested BMI from drape's parametric body model,
  2. the shipped pretrained model's T-shirt for it,
  3. a PyTorch loop of our own that fine-tunes that model's weights so that its T-shirt lowers drape's
     ArcSim-style cloth potential (gravity, the measured knit's stretching and bending, body contact),
     the energies entering the loss through drape.torch_bridge,
  4. the optimised T-shirt (and the body) written as OBJ files.

Run with Debian's interpreter after the README's set-up command:
    PYTHONPATH=build/python /usr/bin/python3 examples/python/drape_example.py --bmi 35 --out garment.obj
"""
import argparse
import time

import numpy as np
import torch

import drape
import drape.torch_bridge as dt

# The scene, inline so that nothing but drape itself is needed: the model's body (the shipped model's is the
# human rig) of the requested shape, the coarse T-shirt in the body's own size by the tailor's rule (as the
# model dresses it) in ArcSim's gray interlock knit, and a smooth penalty contact -- its energy stays finite
# when a step crosses the body, which a plain gradient loop cannot rule out (the barrier cannot).
def scene(model, bmi, height):
    return {
        "body": {**model.body_spec, "shape": {"bmi": bmi, "height": height, "sex": 1}},
        "garment": {"template": "tshirt", "params": {"resolution": "coarse", "size": "auto"}},
        "materials": {"knit": "gray-interlock"},
        "effects": {"gravity": {}, "stretching": {}, "bending": {},
                    "collision": {"stiffness": 1.0e10, "margin": 0.004, "smoothing": 0.02}},
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bmi", type=float, default=35.0)
    ap.add_argument("--height", type=float, default=1.75)
    ap.add_argument("--iterations", type=int, default=30, help="Adam steps on the model's weights")
    ap.add_argument("--lr", type=float, default=1e-4, help="Adam's learning rate")
    ap.add_argument("--model", default=None, help="model file (default: the shipped models/tshirt-coarse-human.h5)")
    ap.add_argument("--out", default="garment.obj", help="the optimised T-shirt (OBJ)")
    ap.add_argument("--body-out", default=None, help="also write the body (OBJ)")
    args = ap.parse_args()

    model = drape.Model.load(args.model)
    body = model.body(bmi=args.bmi, height=args.height)  # float32 [6904, 3] on the human rig
    predicted = model.predict(body)  # float32 [991, 3]; the first call also sets the model up (its garment sizes)
    start = time.perf_counter()
    predicted = model.predict(body)
    print(f"predicted {len(predicted)} garment vertices in {1e3 * (time.perf_counter() - start):.1f} ms "
          "(a second call; the body checked, placed and sized each time)")

    physics = dt.SceneEnergy(drape.Scene(scene(model, args.bmi, args.height)), body.astype(np.float64))
    net = dt.DrapeModel(model)  # its parameters are the model's own weights
    opt = torch.optim.Adam(net.parameters(), lr=args.lr)
    body_t = torch.from_numpy(body)

    def report(label, garment):
        terms = {n: e.value(garment) for n, e in physics.energies.items()}
        print(f"{label}: potential {sum(terms.values()):.4f} J (" +
              ", ".join(f"{n} {v:.4g}" for n, v in terms.items()) + ")")

    report("prediction", predicted)
    start = time.perf_counter()
    best, best_loss = predicted, float("inf")
    for it in range(args.iterations + 1):
        opt.zero_grad()
        garment = net(body_t)
        loss = physics(garment)  # J; backward brings drape's dE/dx into PyTorch
        if loss.item() < best_loss:
            best, best_loss = garment.detach().numpy().copy(), loss.item()
        if it == args.iterations:
            break
        loss.backward()
        opt.step()
    print(f"{args.iterations} Adam steps in {time.perf_counter() - start:.2f} s")
    report("optimised", best)
    move = np.linalg.norm(best - predicted, axis=1)
    print(f"vertices moved {1e3 * move.mean():.2f} mm on average, {1e3 * move.max():.2f} mm at most")

    drape.write_obj(args.out, best, model.assets.garment_faces)
    print(f"wrote {args.out}")
    if args.body_out:
        drape.write_obj(args.body_out, body, model.assets.body_faces)
        print(f"wrote {args.body_out}")


if __name__ == "__main__":
    main()
