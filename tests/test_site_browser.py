"""The reading site in a real browser (``make docs-test``; needs the built site, so it is
deselected from ``make test`` by the ``site`` marker): headless Chromium (Debian's ``chromium``
and ``chromium-driver``) opens the index, clicks the node ``P:inversion`` of the claim graph, lands
on the row's page and finds the paper's statement typeset by MathJax (served from the build)
without an error node; every other claim page is checked the same way, a screenshot of the
P:inversion page is written to ``docs/_build/screenshots/``, and no internal link is broken."""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SITE = ROOT / "docs" / "_build" / "html"
SHOTS = ROOT / "docs" / "_build" / "screenshots"

pytestmark = pytest.mark.site

# Waits (up to 30 s) until MathJax has started: on a loaded machine Chromium was seen to hand the
# page over with the deferred MathJax script not yet run (3 of 68 pages in one run, none on rerun).
_TYPESET = """
const done = arguments[arguments.length - 1];
const deadline = Date.now() + 30000;
(function wait() {
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
    MathJax.startup.promise.then(() => done("ok"), (e) => done("MathJax failed: " + e));
  } else if (Date.now() > deadline) { done("no MathJax"); } else { setTimeout(wait, 50); }
})();
"""


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    assert (SITE / "index.html").is_file(), "build the site first: make docs"
    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium") or "/usr/bin/chromium"
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu",
                "--window-size=1280,1600", "--allow-file-access-from-files"):
        options.add_argument(arg)
    # Chromium's profile, crash database and GTK settings cache go to pytest's temporary folder (a
    # home of its own), never to the user's ~/.config or ~/.cache
    home = tmp_path_factory.mktemp("chromium-home")
    options.add_argument(f"--user-data-dir={home / 'profile'}")
    env = dict(os.environ, HOME=str(home), XDG_CONFIG_HOME=str(home / "config"),
               XDG_CACHE_HOME=str(home / "cache"))
    driver = webdriver.Chrome(options=options, service=Service(
        shutil.which("chromedriver") or "/usr/bin/chromedriver", env=env))
    driver.set_script_timeout(60)
    yield driver
    driver.quit()


def _typeset(driver) -> None:
    assert driver.execute_async_script(_TYPESET) == "ok"


def _statement_rendered(driver) -> int:
    """Number of typeset formulas in the statement; fails on a MathJax error node or on LaTeX
    left untypeset."""
    from selenium.webdriver.common.by import By

    _typeset(driver)
    assert driver.find_elements(By.CSS_SELECTOR, "mjx-merror, [data-mjx-error]") == []
    formulas = driver.find_elements(By.CSS_SELECTOR, ".statement mjx-container")
    for block in driver.find_elements(By.CSS_SELECTOR, ".statement"):
        assert "\\(" not in block.text and "\\[" not in block.text, block.text[:200]
    return len(formulas)


def test_a_graph_node_opens_its_claim_page_with_the_maths_rendered(browser):
    from selenium.webdriver.common.by import By

    browser.get((SITE / "index.html").as_uri())
    _typeset(browser)
    # matplotlib wraps the node's box and its label each in an <a>; the label is on top
    anchors = browser.find_elements(By.CSS_SELECTOR,
                                    '.claim-graph svg a[*|href="claims/P-inversion.html"]')
    assert len(anchors) == 2
    browser.execute_script("arguments[0].scrollIntoView({block: 'center'});", anchors[-1])
    anchors[-1].find_element(By.CSS_SELECTOR, "text, g").click()
    assert browser.current_url.endswith("/claims/P-inversion.html")
    assert browser.find_element(By.TAG_NAME, "h1").text.startswith("P:inversion")
    assert _statement_rendered(browser) >= 3  # Omega, M, gamma inline; the two displays
    assert "holds" in browser.find_element(By.CSS_SELECTOR, ".verdict").text
    SHOTS.mkdir(parents=True, exist_ok=True)
    statement = browser.find_element(By.CSS_SELECTOR, ".statement")
    browser.execute_script("arguments[0].scrollIntoView({block: 'start'});", statement)
    assert browser.save_screenshot(str(SHOTS / "P-inversion.png"))


def test_every_claim_page_renders_its_statement_without_a_maths_error(browser):
    pages = sorted((SITE / "claims").glob("*.html"))
    assert len(pages) >= 60
    with_statement = 0
    for page in pages:
        browser.get(page.as_uri())
        with_statement += _statement_rendered(browser) > 0
    assert with_statement >= 45  # the rows with a passage of the paper


def test_no_internal_link_is_broken():
    sys.path.insert(0, str(ROOT / "docs"))
    from check_links import broken_links

    assert broken_links(SITE) == []


def test_the_sidebar_and_the_index_are_grouped_by_the_papers_sections(browser):
    """The sidebar has one caption per section of CLAIMS.md (then *Beyond the paper*), each row
    a link ``id — short title`` under its section; the index has the same headings, a filter
    that finds a claim by words of its statement, and the errata typeset by MathJax."""
    from selenium.webdriver.common.by import By

    browser.get((SITE / "index.html").as_uri())
    _typeset(browser)
    captions = [c.text for c in browser.find_elements(By.CSS_SELECTOR, ".sphinxsidebar p.caption")]
    assert "Section 4 — the axisymmetric sphere" in captions, captions
    assert any(c.startswith("Beyond the paper") for c in captions), captions
    # the link to P:inversion sits in the list that follows the Section 4 caption
    grouped = browser.find_elements(By.XPATH, (
        "//div[contains(@class,'sphinxsidebar')]//p[contains(@class,'caption')]"
        "[normalize-space()='Section 4 — the axisymmetric sphere']"
        "/following-sibling::ul[1]//a[contains(@href,'claims/P-inversion.html')]"))
    assert len(grouped) == 1 and grouped[0].text.startswith("P:inversion — ")
    headings = [h.text for h in browser.find_elements(By.CSS_SELECTOR, "h3, h4")]
    assert "Section 4 — the axisymmetric sphere" in headings
    assert "Beyond the paper" in [h.text for h in browser.find_elements(By.CSS_SELECTOR, "h2")]
    box = browser.find_element(By.ID, "claim-filter")
    box.send_keys("explicit inverse")
    shown = [tr.text for tr in browser.find_elements(By.CSS_SELECTOR, ".claims-by-section tbody tr")
             if tr.is_displayed()]
    assert len(shown) == 1 and shown[0].startswith("eq:invL3D"), shown
    assert browser.find_elements(By.CSS_SELECTOR, "table.findings mjx-container")
    assert browser.find_elements(By.CSS_SELECTOR, "mjx-merror, [data-mjx-error]") == []
    SHOTS.mkdir(parents=True, exist_ok=True)
    assert browser.save_screenshot(str(SHOTS / "index.png"))


def test_a_corrected_row_shows_its_correction_typeset(browser):
    from selenium.webdriver.common.by import By

    browser.get((SITE / "claims" / "eq-VHgeneraln.html").as_uri())
    _typeset(browser)
    grid = browser.find_elements(By.CSS_SELECTOR, ".correction .correction-grid")
    assert grid and grid[0].find_elements(By.CSS_SELECTOR, "mjx-container")
    assert browser.find_elements(By.CSS_SELECTOR, "table.parts mjx-container")
    assert browser.find_elements(By.CSS_SELECTOR, "mjx-merror, [data-mjx-error]") == []
