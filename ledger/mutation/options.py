r"""The command-line checks both mutation commands make before anything runs: unknown function
names (:func:`unknown_functions`) and the ``--out`` file (:func:`out_problem`)."""

from __future__ import annotations

from pathlib import Path


def unknown_functions(names: list[str], known, list_option: str) -> str | None:
    """The one-line error for the ``--function`` names not in ``known`` (with "did you mean" for
    a near miss and ``list_option``, the command that lists the names), or None when all are
    known. Checked before anything runs."""
    import difflib

    bad = [name for name in names if name not in known]
    if not bad:
        return None
    hints = [f"{name!r}" + "".join(f" (did you mean {m}?)" for m in
                                   difflib.get_close_matches(name, list(known), n=1)) for name in bad]
    return (f"--function: unknown function {', '.join(hints)}; `{list_option}` lists the "
            f"{len(known)} names it takes")


def foreign_out(out: Path | None, what: str) -> str | None:
    """The one-line error when ``--out`` exists and is not ``what`` (a record this program wrote:
    :func:`record.compared_outcomes` reads it), or is a symbolic link; None otherwise. Nothing
    else is ever replaced."""
    from chaplygin_nd.ledger.mutation.record import compared_outcomes

    if out is not None and (out.exists() or out.is_symlink()) and (
            out.is_symlink() or isinstance(compared_outcomes(out), str)):
        return (f"--out {out}: exists and is not {what} this program wrote; give a new file name "
                "(nothing else is replaced)")
    return None


def unwritable_out(out: Path) -> str | None:
    """The one-line error when ``out``'s folder cannot be written (checked by creating a file
    there, as root too: before the run, not after it), or None."""
    from chaplygin_nd.writing import probe_problem

    folder = out.parent
    where = probe_problem(folder) if folder.is_dir() else "no such folder"
    if where:
        return (f"--out {out}: cannot write in {folder} ({where}); give a file in a folder you "
                "can write")
    return None
