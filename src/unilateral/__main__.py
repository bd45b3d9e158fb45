"""``python -m unilateral``: the command line (the same as ``unilateral``)."""

from .cli import main

if __name__ == "__main__":
    main()
