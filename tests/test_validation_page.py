"""The validation page (``knotmech validate`` -> ``DIR/index.html``) as a reviewer reads it.

The page is generated from small canned case results (two PNGs drawn here, numbers with
16-digit floats, nested dicts and lists, a passing, a failing and a raising case), never by
running the real validation cases. The static tests check the HTML; the browser tests open
it in a real headless Chromium (Debian's ``chromium`` + ``chromium-driver``, driven by
selenium) and check that it loads, that every image loads (``naturalWidth > 0``), that the
wide figure is not capped at a thumbnail and opens full size, and that the browser logs no
console error. They skip when Chromium, chromedriver or selenium is missing.
"""

import os
import re
import shutil
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

from knotmech.cli.validate import format_number, write_index  # noqa: E402

SENTENCE_GOOD = "Fake decay rate against the closed form exp(-mu s/R) (made-up reference)."
SENTENCE_BAD = "Fake pinch ratio against Amontons-Coulomb F_t = 2 mu F_n."


def _png(path: Path, width_in: float, height_in: float, dpi: int = 100) -> str:
    fig = Figure(figsize=(width_in, height_in))
    fig.add_subplot().plot([0, 1, 2], [0, 1, 4])
    fig.savefig(path, dpi=dpi)
    return str(path)


@pytest.fixture
def page(tmp_path) -> Path:
    """A validation page from canned results; returns the path of index.html."""
    out = tmp_path / "val"
    out.mkdir()
    wide = _png(out / "wide_figure.png", 24.0, 6.0)  # 2400 x 600 px
    small = _png(out / "small_figure.png", 4.0, 3.0)  # 400 x 300 px
    results = [
        {
            "name": "good_case",
            "verdict": "pass",
            "summary": SENTENCE_GOOD,
            "figures": [wide, small],
            "numbers": {
                "fitted_rate": 0.26227843123456789,
                "steps": 1091.0,
                "tiny": 3.14159265358979e-06,
                "flag": True,
                "source": "DER",
                "missing": None,
                "rates": [0.1472999999, 0.19741234, 0.2639, 0.29123456],
                "long": [i / 7 for i in range(40)],
                "spots": [[0.06, 0.1, True, True], [0.118, 0.2, False, False]],
                "per_mu": {"0.3": {"held": 6, "upper": 0.2500000001}, "0.5": {"held": 16}},
            },
            "checks": {"rate within 1 % of mu_eff": True, "centreline decays at mu": True},
            "notes": ["A made-up note for the reviewer."],
            "seconds": 12.3456,
        },
        {
            "name": "bad_case",
            "verdict": "fail",
            "summary": SENTENCE_BAD,
            "figures": [],
            "numbers": {"ratio": 1.0581234567},
            "checks": {"ratio within 3 % of 1": False, "every run slid": True},
            "notes": [],
            "seconds": 0.5,
        },
        {
            "name": "broken_case",
            "verdict": "error",
            "summary": "",
            "figures": [],
            "numbers": {},
            "checks": {},
            "notes": ["RuntimeError: boom"],
            "traceback": "Traceback (most recent call last):\n  ...\nRuntimeError: boom",
            "seconds": 0.01,
        },
    ]
    return write_index(out, results, quick=True)


# --- the HTML itself -------------------------------------------------------------------


def test_format_number_gives_four_significant_digits():
    assert format_number(0.26227843123456789) == "0.2623"
    assert format_number(1091.0) == "1091"  # integral floats as integers
    assert format_number(3.14159265358979e-06) == "3.142e-6"
    assert format_number(123456.789) == "1.235e5"
    assert format_number(-0.0049999) == "-0.005"
    assert format_number(7) == "7"
    assert format_number(True) == "yes" and format_number(False) == "no"
    assert format_number(float("nan")) == "nan" and format_number("inf") == "inf"


def test_page_states_each_case_its_verdict_and_its_checks(page):
    html = page.read_text()
    assert "1 of 3 cases pass" in html
    for sentence in (SENTENCE_GOOD, SENTENCE_BAD):
        # in the summary table and in the case's own section
        assert html.count(sentence.replace("'", "&#x27;")) == 2
    assert html.count('class="badge pass"') == 1 + 1  # the case and its section heading
    assert html.count('class="badge fail"') == 2 + 1  # the case, its section, the page title
    assert html.count('class="badge error"') == 2
    assert "2 of 2</td>" in html and "1 of 2</td>" in html  # checks held, per case
    assert "&#10007;</span> ratio within 3 % of 1" in html
    assert "<details><summary>traceback</summary>" in html


def test_numbers_are_rounded_and_nested_values_are_tables(page):
    html = page.read_text()
    for raw in ("0.26227843123456789", "0.2622784312", "3.14159265358979", "1091.0", "1.0581234"):
        assert raw not in html, raw
    for shown in (">0.2623<", ">1091<", ">3.142e-6<", ">1.058<", ">DER<", ">yes<"):
        assert shown in html, shown
    assert "0.1473, 0.1974, 0.2639, 0.2912" in html
    assert "40 values in all" in html  # a long list is cut, the JSON has it all
    # nested dicts and lists of rows are tables, not JSON text
    body = html.split("<body>")[1]
    assert "{" not in body and '":' not in body and "[" not in body
    assert re.search(r"<th>per_mu</th><td><table class=\"sub\"><tr><th>0\.3</th>", html)
    assert "<td>0.118</td><td>0.2</td><td>no</td>" in html
    assert ">0.25<" in html  # 0.2500000001 inside the nested dict


def test_every_figure_links_to_its_full_size_png(page):
    html = page.read_text()
    for name in ("wide_figure.png", "small_figure.png"):
        assert f'<a href="{name}" title="open full size"><img src="{name}"' in html
    assert "max-width: 520px" not in html and "max-width: 100%" in html


# --- in a real browser -----------------------------------------------------------------


def _chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


@pytest.fixture(scope="module")
def browser():
    """Headless Chromium through selenium and the system chromedriver (no downloads)."""
    webdriver = pytest.importorskip("selenium.webdriver", reason="selenium is not installed")
    binary, driver_path = _chromium(), shutil.which("chromedriver")
    if binary is None or driver_path is None:
        pytest.skip("no chromium / chromedriver on this machine (apt-get install chromium)")
    os.environ.setdefault("SE_AVOID_STATS", "true")
    options = webdriver.ChromeOptions()
    options.binary_location = binary
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"):
        options.add_argument(arg)
    options.add_argument("--window-size=1280,900")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    from selenium.webdriver.chrome.service import Service

    try:
        driver = webdriver.Chrome(service=Service(executable_path=driver_path), options=options)
    except Exception as exc:  # a broken browser install is not a page defect
        pytest.skip(f"headless chromium did not start: {type(exc).__name__}: {exc}")
    driver.set_page_load_timeout(60)
    yield driver
    driver.quit()


_IMAGES = """
return Array.from(document.images).map(function (img) {
  return {src: img.getAttribute('src'), complete: img.complete,
          natural: img.naturalWidth, shown: img.getBoundingClientRect().width,
          href: img.parentElement.tagName === 'A' ? img.parentElement.href : null};
});
"""


def _open(driver, path: Path):
    driver.get_log("browser")  # drop what earlier pages logged
    driver.get(path.as_uri())
    # lazy images below the fold load once scrolled to; the test scrolls through the page
    driver.execute_script(
        "document.querySelectorAll('img').forEach(function (i) { i.loading = 'eager'; });"
    )
    from selenium.webdriver.support.ui import WebDriverWait

    WebDriverWait(driver, 30).until(
        lambda d: d.execute_script(
            "return document.readyState === 'complete' && "
            "Array.from(document.images).every(function (i) { return i.complete; });"
        )
    )
    images = driver.execute_script(_IMAGES)
    errors = [e for e in driver.get_log("browser") if e.get("level") == "SEVERE"]
    return images, errors


def test_page_loads_in_chromium_with_every_image_and_no_console_error(browser, page):
    images, errors = _open(browser, page)
    assert browser.title == "knotmech validation (quick)"
    assert [i["src"] for i in images] == ["wide_figure.png", "small_figure.png"]
    assert all(i["complete"] and i["natural"] > 0 for i in images), images
    assert errors == [], errors
    wide, small = images
    assert wide["natural"] == 2400 and small["natural"] == 400
    # the wide figure fills the text column (not a 520 px thumbnail), within the window
    assert 900 < wide["shown"] <= 1280
    assert small["shown"] == pytest.approx(400, abs=2)  # small figures at their own size
    # clicking opens the PNG itself, at full size
    browser.get(wide["href"])
    natural = browser.execute_script("return document.images[0].naturalWidth;")
    assert natural == 2400


def test_the_browser_check_sees_a_missing_image(browser, page):
    """Control: the same checks flag a page whose figure is missing."""
    (page.parent / "small_figure.png").unlink()
    images, errors = _open(browser, page)
    assert [i["natural"] > 0 for i in images] == [True, False]
    assert any("small_figure.png" in e.get("message", "") for e in errors), errors


def test_every_real_case_says_what_it_checks_in_one_sentence():
    """Each validation/<name>.py has a SUMMARY for the page: one sentence, what against what."""
    from knotmech.cli.validate import discover_cases, load_case

    for name in discover_cases():
        text = getattr(load_case(name), "SUMMARY", "")
        assert 60 < len(text) < 400, (name, text)
        assert text.endswith(".") and not re.search(r"\.\s+[A-Z]", text), (name, text)
        assert " against " in text, (name, text)
        assert not re.search(r"\w- ", text), (name, text)  # no broken hyphenation
