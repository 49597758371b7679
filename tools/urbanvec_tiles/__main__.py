import sys

from urbanvec_tiles.cli import main

sys.exit(main(sys.argv[1:]))
