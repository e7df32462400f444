"""Process exit codes, shared by every command (listed in `layoutdsl --help`)."""

OK = 0
"""Success; warnings allowed."""
SPEC_ERRORS = 1
"""The input has errors (diagnostics printed)."""
USAGE = 2
"""Usage, I/O or internal error."""
NO_LAYOUT = 3
"""No layout: the spec is infeasible, the time limit passed with no layout, or a solved
layout failed independent verification (nothing is written)."""

EPILOG = """\
exit codes:
  0  OK (warnings allowed)
  1  the input has errors
  2  usage, I/O or internal error
  3  no layout: infeasible spec, time limit with no layout, or failed verification
"""
