"""Options shared by every test folder."""

from __future__ import annotations


def pytest_addoption(parser) -> None:
    parser.addoption(
        "--update-goldens",
        action="store_true",
        default=False,
        help="rewrite golden/snapshot files from the current output instead of comparing",
    )
