import sys

from urbanvec_tiles.cli import main

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
