"""mypy's stubtest on the module maneuvermap and its stubs (CTest
python.the_type_stubs_and_the_module_have_the_same_names).

stubtest imports the module and reports every name the stubs lack or have in excess, and every
class whose stub disagrees with it. pybind11 makes it report two things of many classes that are
not faults of the stubs, each let through here only where it holds:
- "metaclass differs": every bound class has the metaclass pybind11_type, which a stub cannot name;
- "stub does not have *args argument": a class without a bound constructor has pybind11's
  ``__init__(self, *args, **kwargs)``, which only raises TypeError; its stub declares none.
Any other report fails the test (exit code 1). stubtest cannot see the signatures of compiled
functions; make_stubs.py --check compares those.
"""
import importlib
import re
import subprocess
import sys

METACLASS = re.compile(r"^(?P<name>\S+) is inconsistent, metaclass differs$")
NO_CONSTRUCTOR = re.compile(r'^(?P<name>\S+)\.__init__ is inconsistent, stub does not have \*args argument "args"$')


def runtime_object(name: str) -> object:
    """The object of a dotted name: the longest importable module, then attributes."""
    parts = name.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            value: object = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        for attribute in parts[cut:]:
            value = getattr(value, attribute)
        return value
    raise ImportError(name)


def benign(line: str) -> bool:
    if match := METACLASS.match(line):
        return type(runtime_object(match["name"])).__name__ == "pybind11_type"
    if match := NO_CONSTRUCTOR.match(line):
        cls = runtime_object(match["name"])
        return isinstance(cls, type) and type(cls.__dict__.get("__init__")).__name__ == "wrapper_descriptor"
    return False


def main() -> int:
    run = subprocess.run(
        [sys.executable, "-c",
         "import sys; from mypy.stubtest import main; sys.argv = ['stubtest', '--concise', 'maneuvermap']; "
         "sys.exit(main())"],
        capture_output=True, text=True)
    lines = [line for line in run.stdout.splitlines() if line.strip()]
    faults = [line for line in lines if not benign(line)]
    print(f"stubtest: {len(lines)} reports, {len(lines) - len(faults)} of them pybind11's (see the docstring)")
    for line in faults:
        print(line)
    if run.stderr.strip():
        print(run.stderr, file=sys.stderr)
    if faults or (run.returncode not in (0, 1)) or (run.returncode == 1 and not lines):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
