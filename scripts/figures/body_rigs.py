#!/usr/bin/env python3
"""Bodies of several models side by side, flat-shaded front and side: the parametric body's two rigs and
MakeHuman's at the same sex, height and BMI (docs/bodies.md, "The human rig").

    /usr/bin/python3 scripts/figures/body_rigs.py --out rigs.png [--drape build/bin/drape]
        [--models parametric,parametric:rig=human,makehuman] [--bodies 0:1.65:22,1:1.80:25,...]

Each row is one body (sex:height:BMI), each column one model (parameters after a colon, as in
body_proportions.py); a model that cannot reach a body leaves its cell with the reason. Bodies are made
with `drape body`, drawn with shaded_views.py and laid out in one self-contained HTML page (kept beside
the PNG) that headless Chromium turns into the PNG.
"""
import argparse
import base64
import html
import pathlib
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from body_proportions import body_model_args  # noqa: E402

DEFAULT_BODIES = "0:1.65:22,1:1.80:25,0:1.62:32,1:1.52:14,0:1.50:65,1:2.00:10"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="the figure (.png); the .html beside it")
    ap.add_argument("--drape", default="build/bin/drape")
    ap.add_argument("--models", default="parametric,parametric:rig=human,makehuman")
    ap.add_argument("--bodies", default=DEFAULT_BODIES, help="sex:height:BMI, comma-separated")
    ap.add_argument("--size", type=int, default=260, help="pixels per view")
    a = ap.parse_args()
    out = pathlib.Path(a.out).resolve()
    page = out.with_suffix(".html")
    models = a.models.split(",")
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for body in a.bodies.split(","):
            sex, height, bmi = body.split(":")
            cells = []
            for model in models:
                name = f"{model.replace(':', '_').replace('=', '_')}_{sex}_{height}_{bmi}"
                mesh = pathlib.Path(folder) / f"{name}.obj"
                run = subprocess.run([a.drape, "body", *body_model_args(model), "--sex", sex, "--height", height,
                                      "--bmi", bmi, "--out", str(mesh)], capture_output=True, text=True)
                if run.returncode != 0:
                    reason = run.stderr.strip().splitlines()[-1] if run.stderr.strip() else "failed"
                    cells.append(f'<td class="miss">{html.escape(reason[:160])}</td>')
                    continue
                png = pathlib.Path(folder) / f"{name}.png"
                subprocess.run([sys.executable, str(HERE / "shaded_views.py"), str(mesh), "--views", "front,left",
                                "--size", str(a.size), "--out", str(png)], check=True, capture_output=True)
                data = base64.b64encode(png.read_bytes()).decode()
                cells.append(f'<td><img src="data:image/png;base64,{data}"></td>')
            who = f"{'woman' if float(sex) < 0.5 else 'man'}, {height} m, BMI {bmi}"
            rows.append(f"<tr><th>{who}</th>{''.join(cells)}</tr>")
    head = "".join(f"<th>{html.escape(m)}</th>" for m in models)
    page.write_text(
        "<html><head><style>body{font-family:sans-serif;margin:8px} td,th{padding:2px 6px;font-size:13px}"
        f" img{{height:{a.size}px}} td.miss{{color:#888;width:{2 * a.size}px;white-space:normal}}</style></head><body>"
        f"<table><tr><th></th>{head}</tr>{''.join(rows)}</table></body></html>")
    width = 140 + len(models) * (2 * a.size + 20)
    height_px = 40 + len(rows) * (a.size + 8)
    subprocess.run(["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                    f"--screenshot={out}", f"--window-size={width},{height_px}", page.as_uri()],
                   check=True, capture_output=True)
    print(f"wrote {out} and {page}")


if __name__ == "__main__":
    main()
