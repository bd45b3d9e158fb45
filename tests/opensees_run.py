"""Run a script of ``tests/opensees_scripts`` with OpenSeesPy or with ``unilateral.opensees``.

``python tests/opensees_run.py SCRIPT opensees|unilateral`` prints the script's JSON; the second
runs the script's text with its import changed to ``import unilateral.opensees as ops`` only.
"""

import os
import sys

IMPORT = "import openseespy.opensees as ops"


def source(path, which):
    text = open(path).read()
    assert text.count(IMPORT) == 1, f"{path} must import openseespy.opensees as ops once"
    return text if which == "opensees" else text.replace(IMPORT, "import unilateral.opensees as ops")


if __name__ == "__main__":
    path, which = sys.argv[1], sys.argv[2]
    sys.argv = [path]
    code = compile(source(path, which), os.path.abspath(path), "exec")
    exec(code, {"__name__": "__main__", "__file__": os.path.abspath(path)})
