"""The `drape` console script of a pip-installed package: runs the drape program shipped inside it
(drape/bin/drape), which finds the package's plugins, model, scenes and graphs beside itself."""
import os
import sys


def main():
    program = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "drape")
    if not os.access(program, os.X_OK):
        sys.exit(f"drape: {program} is missing: this package was not installed by pip (a build tree runs build/bin/drape)")
    os.execv(program, [program, *sys.argv[1:]])


if __name__ == "__main__":
    main()
