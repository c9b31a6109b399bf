"""``pinlin analyze --animate mode1.gif --mode 1``: the animation is written."""

from __future__ import annotations

import pytest

from pinlin.cli import main

PIL = pytest.importorskip("PIL.Image")
plot = pytest.importorskip("pinlin.plot")


def test_animation_of_the_first_mode_is_written_as_gif(capsys, tmp_path):
    target = tmp_path / "mode1.gif"
    code = main(["analyze", "--animate", str(target), "--mode", "1"])
    out = capsys.readouterr()
    assert code == 0, out.err
    assert "Stability:" in out.out  # the report comes first
    assert target.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    with PIL.open(target) as gif:
        assert gif.n_frames == plot.animation.DEFAULT_FRAMES
        assert gif.size[0] > 100 and gif.size[1] > 100

