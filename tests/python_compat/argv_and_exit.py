"""Prints its argv, __name__ and a module beside it, then exits with the status argv[1] names (for these tests)."""

import json
import sys

import beside_script

print(json.dumps([sys.argv, __name__, beside_script.VALUE]))
sys.exit(int(sys.argv[1]))
