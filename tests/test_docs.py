"""The documentation site builds with no warning (`sphinx-build -W`): every page, every
API docstring, every figure and link it names; and its pages speak to a user (no
development history, no path outside the repository, no placeholder left).  The default
run builds the gallery's pages without running the examples (each example has its own
tests: test_examples, test_fit); the whole build, examples run, is `slow`."""
import html
import re
import subprocess
import sys

import pytest

from conftest import ENV, REPO

pytest.importorskip("sphinx")
pytest.importorskip("myst_parser")
pytest.importorskip("numpydoc")
pytest.importorskip("pydata_sphinx_theme")

DOCS = REPO / "docs"
PAGES = {"index", "getting-started", "one-shell", "fit", "map", "studies", "notebook", "materials",
         "cavities", "adhesion-range", "thin-shells", "figures-gallery", "scaling-out",
         "domain", "validation", "performance", "theory", "api"}

# what a user's page must not hold: the machinery of our development
NOT_FOR_USERS = {
    "a path outside the repository": r"\.\./shared|/work/|DESIGN\.md",
    "an issue number": r"\bissues? #?\d+",
    "a commit hash": r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}\b",
    "an in-house tool": r"\bfarm-bench\b",
}
PLACEHOLDER = re.compile(r"^[A-Z][A-Z0-9]*_[A-Z0-9_]+$", re.M)   # a line that is one NAME_TO_FILL


def _build(out, *overrides):
    """sphinx-build -W into out, with the config overrides given (-D name=value)."""
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b",
                          "html", *(a for o in overrides for a in ("-D", o)), str(DOCS),
                          str(out)],
                         env=dict(ENV, MPLBACKEND="Agg"), capture_output=True, text=True,
                         timeout=900)
    return run, out


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The site with the gallery's pages written but its examples not run."""
    return _build(tmp_path_factory.mktemp("docs") / "html", "plot_gallery=0")


@pytest.fixture(scope="module")
def site_with_gallery(tmp_path_factory):
    """The whole site as the docs extra builds it: every example run (even one whose
    output an earlier build left in docs/gallery)."""
    return _build(tmp_path_factory.mktemp("docs_gallery") / "html",
                  "sphinx_gallery_conf.run_stale_examples=1")


def _text(page):
    """The visible text of a built page."""
    raw = re.sub(r"<(script|style)\b.*?</\1>", " ", page.read_text(), flags=re.S)
    return html.unescape(re.sub(r"<[^>]+>", " ", raw))


def test_docs_build_without_warnings(site):
    run, out = site
    assert run.returncode == 0, run.stderr[-3000:]
    assert PAGES <= {p.stem for p in out.glob("*.html")}
    api = (out / "api.html").read_text()
    for name in ("solve_case", "R_mm", "run_study", "open_results", "CaseResult",
                 "paper_study", "load_study", "Catalogue", "jkr_P_star_N"):
        assert name in api, name


# each example of the gallery, run by the build: what only its output holds
GALLERY = {"ex01_base_case": r"P\* = -1\.\d+ N", "ex02_hertz_table": r"frictionless \(coarse mesh\)",
           "ex03_mooney_rivlin": r"relaxation paths 18/18 shells",
           "ex04_fit_curve": r"fit: \d+\.\d s", "ex05_design": r"map and FE case agree"}


def test_the_gallery_has_a_page_for_every_example(site):
    run, out = site
    assert run.returncode == 0, run.stderr[-3000:]
    examples = {p.stem for p in (REPO / "examples").glob("ex*.py")}
    assert examples == set(GALLERY), "an example missing from the gallery's checks"
    assert examples <= {p.stem for p in (out / "gallery").glob("ex*.html")}


@pytest.mark.slow      # runs every example (about 3 min on 2 cores); their tests run them too
def test_the_gallery_runs_every_example(site_with_gallery):
    run, out = site_with_gallery
    assert run.returncode == 0, run.stderr[-3000:]
    for name, pattern in GALLERY.items():
        text = " ".join(_text(out / "gallery" / f"{name}.html").split())
        assert re.search(pattern, text), (name, pattern)


def test_pages_hold_nothing_of_the_development(site):
    run, out = site
    assert run.returncode == 0, run.stderr[-3000:]
    found = [f"{page.name}: {what}: ...{text[max(0, m.start() - 50):m.end() + 30]}..."
             for page in sorted(out.glob("*.html")) if page.stem in PAGES
             for text in [_text(page)]
             for what, pattern in NOT_FOR_USERS.items()
             for m in re.finditer(pattern, text)]
    assert not found, "\n".join(found)


def test_no_placeholder_left_in_a_page():
    """A benchmark result still to be filled in (a line such as PAIRED_WORKFLOW)."""
    left = [f"docs/{p.name}:{p.read_text()[:m.start()].count(chr(10)) + 1}: {m.group()}"
            for p in sorted(DOCS.glob("*.md")) for m in PLACEHOLDER.finditer(p.read_text())]
    assert not left, "placeholders left in the documentation:\n" + "\n".join(left)


def _rows(text):
    """Markdown table rows by their first cell."""
    return {line.split("|")[1].strip(): line.strip() for line in text.splitlines()
            if line.startswith("| ") and line.count("|") > 2}


def test_validation_page_states_the_readme_numbers():
    """The validation page and the README's validation tables say the same where both
    have a row (the README's numbers are the ones the validation tests pin)."""
    readme = _rows((REPO / "README.md").read_text())
    page = _rows((DOCS / "validation.md").read_text())
    differ = [f"README:   {readme[k]}\ndocs:     {page[k]}" for k in page
              if k in readme and k not in ("check", "quantity", "---")
              and readme[k] != page[k]]
    assert not differ, "\n".join(differ)
