"""`--out-root DIR`, shared by the generators of tools/.

Every generator writes its files at fixed paths of the repository (tests/data/..., tools/cases/...,
tests/common/..., examples/mech/...). With `--out-root DIR` it writes them at the same relative
paths under DIR instead, and reads the generated files it depends on (a drawing, a file whose
generated block it replaces) from there too: DIR is a repository-shaped tree. Without it, DIR is
the repository, i.e. the files are regenerated in place. tools/generate_all.py --check uses it to
regenerate every table into a temporary directory and compare it with the committed one.
"""

import os

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def split(argv):
    """(DIR, argv without `--out-root DIR`); DIR is the repository when the option is absent."""
    argv = list(argv)
    root = REPO
    for i, a in enumerate(argv):
        if a == "--out-root":
            if i + 1 >= len(argv):
                raise SystemExit("--out-root needs a directory")
            root = os.path.abspath(argv[i + 1])
            del argv[i:i + 2]
            break
        if a.startswith("--out-root="):
            root = os.path.abspath(a.split("=", 1)[1])
            del argv[i]
            break
    return root, argv


def path(root, *rel):
    """root/rel..., its directory created."""
    p = os.path.join(root, *rel)
    os.makedirs(os.path.dirname(p), exist_ok=True)
    return p
