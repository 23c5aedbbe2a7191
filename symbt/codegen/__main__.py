"""``python -m symbt.codegen [--check] [--out DIR]`` (same as ``symbt codegen``)."""
import sys

from . import main

sys.exit(main())
