"""The study files shipped inside the package, so that any install can run them.

`paper` is the paper's study (the repository's `workflow.yaml`: the base case and the
one-factor sweeps, 11 shells on the default mesh); `mooney-rivlin` sweeps C01/C10 for the
base shell (`examples/study_mooney_rivlin.yaml`, coarse mesh); `map` and `map-coarse`
build the pull-off maps shipped with the package (`shell-adhesion map build`).  Each is a path to a YAML
file in `shell_adhesion/data`:

    import shell_adhesion as sa
    sa.run_study(sa.examples.paper_study(), out="results/")

or, from the command line, a copy to edit:

    shell-adhesion example paper > workflow.yaml
    shell-adhesion run workflow.yaml --out results/
"""
from pathlib import Path

DATA = Path(__file__).parent / "data"
# the name `shell-adhesion example NAME` takes -> its file in DATA
STUDIES = {"paper": "paper.yaml", "mooney-rivlin": "mooney_rivlin.yaml",
           "map": "pull_off_map.yaml", "map-coarse": "pull_off_map_coarse.yaml"}


def study_path(name: str) -> Path:
    """Path of the shipped study `name` (a key of STUDIES)."""
    if name not in STUDIES:
        raise ValueError(f"example: {name!r} must be one of {', '.join(STUDIES)}")
    return DATA / STUDIES[name]


def study_text(name: str) -> str:
    """The YAML text of the shipped study `name`, as written in its file."""
    return study_path(name).read_text(encoding="utf-8")


def paper_study() -> Path:
    """Path of the paper's study (the YAML of the repository's `workflow.yaml`)."""
    return study_path("paper")


def mooney_rivlin_study() -> Path:
    """Path of the Mooney-Rivlin study (the YAML of `examples/study_mooney_rivlin.yaml`)."""
    return study_path("mooney-rivlin")
