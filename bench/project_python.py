"""The interpreter for bench/*.py: a script that needs a package found only in the project's .venv
(scripts/setup-tools puts NVIDIA's FLIP, PyPI flip-evaluator, there) re-runs itself under
.venv/bin/python3, so `bench/sweep_report.py DIR` works from any python3 once setup-tools has run.
Without .venv, or already inside it, the script goes on where it is and skips what is missing."""
import importlib.util
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def importable(module):
    return importlib.util.find_spec(module) is not None


def interpreter_for(modules, root=ROOT, prefix=None, have=importable):
    """The .venv interpreter to re-run under, or None: when this interpreter imports every module,
    when root has no .venv/bin/python3, or when this interpreter is that environment's (prefix:
    sys.prefix, which names the environment; its python3 is a link to the system one)."""
    if all(have(m) for m in modules):
        return None
    venv = os.path.join(root, ".venv")
    python = os.path.join(venv, "bin", "python3")
    if not os.access(python, os.X_OK):
        return None
    if os.path.realpath(prefix if prefix is not None else sys.prefix) == os.path.realpath(venv):
        return None
    return python


def use_project_venv(modules):
    """Replaces this process by the same script under the project's .venv when that holds a module
    this interpreter lacks (see interpreter_for); returns otherwise."""
    python = interpreter_for(modules)
    if python:
        sys.stdout.flush()
        os.execv(python, [python, os.path.abspath(sys.argv[0])] + sys.argv[1:])
