"""What `drape simulate` printed about a drape, as numbers: the figure and check scripts read it the same way."""
import re


def parse_simulate_output(text):
    """settled (bool), iterations, p (percent), crossings (garment and body edges through the other surface),
    seconds and size (size: auto's choice, '' without) from drape simulate's output; None where it says nothing."""
    def number(pattern, kind=float):
        m = re.search(pattern, text)
        return kind(m.group(1)) if m else None

    m = re.search(r"surface crossings (\d+) garment edges / (\d+) body edges", text)
    size = re.search(r"size auto: .*: size (\S+)", text)
    return dict(settled=bool(re.search(r"^settled", text, re.M)),
                iterations=number(r"after \d+ steps, (\d+) Newton iterations", int),
                p=number(r"penetration p = ([0-9.]+)%"),
                crossings=int(m.group(1)) + int(m.group(2)) if m else None,
                seconds=number(r", time ([0-9.]+) s"),
                size=size.group(1) if size else "")
