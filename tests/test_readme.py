"""The README stays a screen or two (at most 12 KB) and every manual page it links to
exists and is built into the site (docs/build_pages.py MANUAL): one copy of each text, no dead link."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"


def test_readme_fits_on_a_screen_or_two():
    assert len(README.read_bytes()) <= 12 * 1024


def test_every_manual_page_the_readme_links_exists_and_is_on_the_site():
    links = re.findall(r"\]\((docs/pages/[\w.-]+\.md)\)", README.read_text(encoding="utf-8"))
    assert links, "the README links the manual"
    site = (ROOT / "docs" / "build_pages.py").read_text(encoding="utf-8")
    missing = [p for p in links if not (ROOT / p).is_file()]
    unbuilt = [p for p in links if f'"pages/{Path(p).stem}"' not in site]
    assert missing == [] and unbuilt == []


def test_the_install_line_says_what_a_wheel_without_the_extra_fast_leaves_open(monkeypatch):
    """A plain install has no heyoka: the evidence rows say ``open`` with the install command of
    ``proofs/drawn_common.without_heyoka``; the README says so where it tells how to install, with
    the same command."""
    from chaplygin_nd.proofs import drawn_common
    from chaplygin_nd.simulate.integrators import heyoka_taylor

    monkeypatch.setattr(heyoka_taylor, "available", lambda: False)
    reason = drawn_common.without_heyoka()
    command = re.search(r"pip install '[^']+'", reason).group(0)
    text = " ".join(README.read_text(encoding="utf-8").split())
    install = text[text.index("Installed from a wheel"):text.index("## What `make verify` prints")]
    assert command.replace("pip install ", "") in install and "`open`" in install, install
    assert reason.split(":")[0] in install  # "not measured here"


def test_the_sample_of_make_verify_is_in_the_order_verify_prints():
    """``verify`` prints the rows as they finish (not in ledger order: the README says so), then
    the generated/ check, then the totals (ledger/__main__.py); the sample shows that order."""
    text = README.read_text(encoding="utf-8")
    sample = text[text.index("## What `make verify` prints"):].split("```")[1].splitlines()
    source = (ROOT / "ledger" / "__main__.py").read_text(encoding="utf-8")
    assert source.index('say("generated/ is up to date') < source.index("say(report.summary(")
    generated = next(i for i, ln in enumerate(sample) if ln.startswith("generated/ is up to date"))
    totals = next(i for i, ln in enumerate(sample) if re.match(r"\d+ rows: ", ln))
    assert sample[1] == "seed 20261121" and sample[2].startswith("id ") and generated < totals
    assert "the rows print as they finish" in " ".join(text.split())
