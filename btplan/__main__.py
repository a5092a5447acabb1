"""`python -m btplan` runs the command line, for when the `btplan` script is not on PATH."""

from btplan.cli import main

if __name__ == "__main__":
    main()
