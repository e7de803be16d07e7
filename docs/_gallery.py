"""The command-line arguments each example gets when the docs are built (sphinx-gallery's
`reset_argv`): the coarse mesh, and for the Mooney-Rivlin sweep an output folder inside
the generated gallery, so the build writes nothing into the repository's tracked files."""
from pathlib import Path


def argv(gallery_conf, script_vars):
    name = Path(script_vars["src_file"]).name
    if name.startswith("ex03_"):
        out = Path(script_vars["target_file"]).parent / "ex03_output"
        return ["--mesh", "coarse", "--out", str(out), "--catalogue", str(out / "catalogue")]
    return ["coarse"]
