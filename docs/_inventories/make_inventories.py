"""Write the intersphinx inventories the documentation links Python's and numpy's names through.

The build stays offline, so the inventories are bundled (``python.inv``, ``numpy.inv``).  They hold only
the external names pinlin's pages reference, each at its real address on the project's documentation
site.  This script writes them with Sphinx's own inventory writer: it builds, per project, a stub
Sphinx project whose pages sit at the real site's paths (``library/collections.abc`` ->
``library/collections.abc.html``) and declare each name with the Python domain's directives, so that
the anchor is the name's real one (``#collections.abc.Sequence``); ``:canonical:`` adds the private
module path that annotations resolve to (``concurrent.futures._base.Executor``).  Run it after the
docs start referencing a new external name (``python docs/_inventories/make_inventories.py``), and
check each new address on the site.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from sphinx.application import Sphinx

HERE = Path(__file__).resolve().parent

#: project -> (site, version, {page path on the site: [(directive, name, canonical name or None)]})
PROJECTS = {
    "python": ("https://docs.python.org/3", "3", {
        "library/collections.abc": [("class", f"collections.abc.{n}", None)
                                    for n in ("Callable", "Collection", "Iterable", "Iterator", "Mapping", "Sequence")],
        "library/os": [("class", "os.PathLike", None)],
        "library/pathlib": [("class", "pathlib.Path", None)],
        "library/dataclasses": [("function", "dataclasses.replace", None)],
        "library/difflib": [("function", "difflib.get_close_matches", None)],
        "library/concurrent.futures": [
            ("class", "concurrent.futures.Executor", "concurrent.futures._base.Executor"),
            ("class", "concurrent.futures.Future", "concurrent.futures._base.Future"),
        ],
    }),
    "numpy": ("https://numpy.org/doc/stable", "stable", {
        "reference/generated/numpy.ndarray": [("class", "numpy.ndarray", None)],
        "reference/generated/numpy.polynomial.polynomial.Polynomial": [
            ("class", "numpy.polynomial.polynomial.Polynomial", "numpy.polynomial.Polynomial"),
        ],
    }),
}


def stub_page(entries) -> str:
    lines = ["Stub", "====", ""]
    for directive, name, canonical in entries:
        lines.append(f".. py:{directive}:: {name}")
        if canonical:
            lines.append(f"   :canonical: {canonical}")
        lines.append("")
    return "\n".join(lines)


def write(project: str) -> Path:
    _, version, pages = PROJECTS[project]
    with tempfile.TemporaryDirectory() as tmp:
        src, out = Path(tmp, "src"), Path(tmp, "out")
        for page, entries in pages.items():
            path = src / f"{page}.rst"
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(stub_page(entries), encoding="utf-8")
        toctree = "\n".join(f"   {page}" for page in pages)
        (src / "index.rst").write_text(f"Stub\n====\n\n.. toctree::\n\n{toctree}\n", encoding="utf-8")
        (src / "conf.py").write_text(f"project = {project!r}\nversion = release = {version!r}\n", encoding="utf-8")
        Sphinx(str(src), str(src), str(out), str(Path(tmp, "doctrees")), "html", status=None,
               warningiserror=True).build()
        target = HERE / f"{project}.inv"
        shutil.copyfile(out / "objects.inv", target)
    return target


if __name__ == "__main__":
    if len(sys.argv) > 1:
        print(write(sys.argv[1]))
    else:  # one process per project: Sphinx registers its nodes once per process
        for name in PROJECTS:
            subprocess.run([sys.executable, __file__, name], check=True)
