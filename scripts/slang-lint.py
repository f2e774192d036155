"""A second, stricter Verilog front end over an emitted design: slang
(PyPI pyslang, installed by scripts/setup.sh into build/venv) elaborates
TOP from the design's filelist.f with every warning on (-Weverything) and
prints its diagnostics. Exit status 0 when it reports none, 1 otherwise.

    build/venv/bin/python scripts/slang-lint.py DIR TOP
"""
import sys
from pathlib import Path

try:
    import pyslang
except ImportError:
    print("pyslang is not installed in this Python; run `bash scripts/setup.sh` "
          "(the PyPI package pyslang in build/venv)", file=sys.stderr)
    sys.exit(2)


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    directory, top = Path(sys.argv[1]), sys.argv[2]
    files = [str(directory / line.strip()) for line in (directory / "filelist.f").read_text().splitlines()
             if line.strip() and not line.startswith(("+", "-", "//"))]
    driver = pyslang.driver.Driver()
    driver.addStandardArgs()
    command = " ".join(["slang", "--top", top, "-Weverything", *files])
    if not driver.parseCommandLine(command, pyslang.driver.CommandLineOptions()):
        return 2
    if not driver.processOptions() or not driver.parseAllSources():
        return 1
    compilation = driver.createCompilation()
    driver.reportCompilation(compilation, False)  # prints the diagnostics
    count = len(compilation.getAllDiagnostics())
    errors = driver.diagEngine.numErrors
    print(f"slang -Weverything on {top}: {count} diagnostic(s), {errors} error(s)")
    return 0 if count == 0 and errors == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
