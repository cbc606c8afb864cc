"""Helpers shared by the command-line tests (tests/test_cli_ux.py, tests/test_user_inputs.py)."""

from __future__ import annotations


def exit_code(call, argv) -> int:
    """The exit status of ``call(argv)``, whether it returns it or argparse exits with it."""
    try:
        return call(argv)
    except SystemExit as exc:
        return exc.code


def one_error_line(capsys) -> str:
    """The one line ``error: ...`` the command printed on stderr (asserted to be alone)."""
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: "), err
    return err[0]
