"""The shell commands of the user guide and the README run as printed, from an empty folder.

Every line starting with ``pinlin `` in a ```bash block of ``docs/guide/*.md``
and ``README.md`` is run (in-process, through :func:`pinlin.cli.main`) with an
empty temporary directory as the working directory, so a path relative to the
repository would fail.  A command that draws (``--plot``, ``--animate``) needs
matplotlib: the docs say so (``pinlin[plot]`` on its line or in the sentence
before its block), and the test is skipped without it.  Each command writes
exactly the files it names and nothing else.
"""

from __future__ import annotations

import importlib.util
import re
import shlex
from pathlib import Path

import pytest

from pinlin.cli import EXIT_OK, main

ROOT = Path(__file__).resolve().parents[2]
DOCS = sorted(ROOT.joinpath("docs", "guide").glob("*.md")) + [ROOT / "README.md"]
#: Options whose argument is a file the command writes.
OUTPUTS = ("--json", "--plot", "--animate")
#: Options that draw with matplotlib (the ``plot`` extra).
DRAWING = ("--plot", "--animate")


def commands(path: Path) -> list[tuple[str, str]]:
    """(command, the text before its block) of each ``pinlin ...`` line of the ```bash blocks of a file."""
    out = []
    lines = path.read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines):
        if lines[i].strip() == "```bash":
            j = lines.index("```", i + 1)
            before = " ".join(lines[max(0, i - 3) : i])
            for line in lines[i + 1 : j]:
                if line.startswith("pinlin "):
                    out.append((line, before))
            i = j
        i += 1
    return out


CASES = [(path.relative_to(ROOT).as_posix(), line, before) for path in DOCS for line, before in commands(path)]


def test_the_docs_have_commands_for_every_subcommand():
    names = {shlex.split(line, comments=True)[1] for _, line, _ in CASES}
    assert names == {"analyze", "sweep", "campbell"}
    assert len(CASES) >= 12
    assert not any("scenes/" in line or "my_scene" in line for _, line, _ in CASES)  # runnable from any folder


@pytest.mark.parametrize(("doc", "line", "before"), CASES, ids=[f"{d}: {line[:60]}" for d, line, _ in CASES])
def test_a_documented_command_runs_from_an_empty_folder(doc, line, before, tmp_path, monkeypatch, capsys):
    argv = shlex.split(line, comments=True)[1:]
    if any(option in argv for option in DRAWING):
        assert "pinlin[plot]" in line or "pinlin[plot]" in before, f"{doc}: {line!r} draws: say it needs pinlin[plot]"
        if importlib.util.find_spec("matplotlib") is None:
            pytest.skip("draws with matplotlib (pinlin[plot])")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    try:
        code = main(argv)
    except SystemExit as exc:  # --help
        code = exc.code
    out, err = capsys.readouterr()
    assert code == EXIT_OK, f"{doc}: {line!r} failed: {err}"
    assert err == ""
    named = {argv[k + 1] for k, word in enumerate(argv) if word in OUTPUTS}
    assert {p.name for p in tmp_path.iterdir()} == named
    for name in named:
        assert (tmp_path / name).stat().st_size > 0 and f"wrote {name}" in out
    if "--help" not in argv:
        assert re.search(r"^Total .* \(Python start-up and imports not included\)$", out, re.MULTILINE)


def test_the_guide_runs_the_bundled_turntable_by_name():
    lines = [line for doc, line, _ in CASES if doc == "docs/guide/cli.md"]
    assert any(line.startswith("pinlin campbell turntable.toml --joint table") for line in lines)
