"""Bad input for the diagnostic tools: one line naming the file, the place and what was expected, exit 2
(the brief's rule for every loader; tests/tools/bad_input_test.py runs each tool on missing, truncated and
malformed input).

  from tool_input import BadInput, run
  if __name__ == "__main__":
      run(main, "tools/x.py DIR ROW", args=(2, 3))

run() checks the positional argument count (args: (min, max), max None = unbounded; options after the
positionals are the tool's own), then calls main() and turns what bad input raises into that one line:
Arguments (argparse, its errors on one line),
BadInput (raised by read_pfm and the tools' own checks, with the file and what it expected), a missing or
unreadable file (OSError), and the ValueError / KeyError / IndexError a folder of the wrong kind leads to
(a CSV without the column, an image of another size). Anything else is a bug in the tool and keeps its
traceback. A ValueError / KeyError / IndexError can also be a bug in the tool's own arithmetic, which this
one line would hide: its line says so, and BOUNCE_TOOL_TRACEBACK=1 lets every exception through with its
traceback (the session-18 review).
"""
import argparse
import os
import sys


class BadInput(Exception):
    """Input that is not what the tool reads: `path` (or a place), what was found, what was expected."""

    def __init__(self, path, what, expected):
        super().__init__(f"{path}: {what} (expected {expected})")


class Arguments(argparse.ArgumentParser):
    """argparse with the rule's one line: its usage error on one line, exit 2 (argparse prints several)."""

    def error(self, message):
        _fail(f"{self.prog}: {message} (expected usage: {' '.join(self.format_usage().split()[1:])})")


def run(main, usage, args=(1, None)):
    tool = os.path.basename(sys.argv[0])
    positional = [a for a in sys.argv[1:] if not a.startswith("--")]
    lo, hi = args
    if len(positional) < lo or (hi is not None and len(positional) > hi):
        _fail(f"{tool}: {len(positional)} arguments (expected usage: {usage})")
    if os.environ.get("BOUNCE_TOOL_TRACEBACK") == "1":
        sys.exit(main() or 0)
    try:
        code = main()
    except BadInput as e:
        _fail(str(e))
    except OSError as e:
        _fail(f"{e.filename or tool}: {e.strerror or e} (expected the files of the usage: {usage})")
    except (ValueError, KeyError, IndexError) as e:
        _fail(f"{tool}: {type(e).__name__}: {e} (expected the folders and files of the usage: {usage}; "
              "if they are, rerun with BOUNCE_TOOL_TRACEBACK=1 for the tool's traceback)")
    sys.exit(code or 0)


def _fail(line):
    print(line.replace("\n", " "), file=sys.stderr)
    sys.exit(2)
