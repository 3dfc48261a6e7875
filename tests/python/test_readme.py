"""The README's Python example runs as written (copied out of README.md, not retyped here): it
plans unwrap at 360 degrees, plots the writhe over time into writhe.png and renders the last
state."""

import pathlib
import re

import numpy as np

README = pathlib.Path(__file__).resolve().parents[2] / "README.md"


def python_example():
    text = README.read_text()
    section = text[text.index("## Python") :]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_readme_python_example_runs(tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")  # headless
    monkeypatch.chdir(tmp_path)
    scope = {}
    exec(compile(python_example(), str(README) + " (Python example)", "exec"), scope)
    assert scope["report"]["success"] is True
    writhe = np.asarray(scope["writhe"])
    assert abs(writhe[0]) > 0.9 and abs(writhe[-1]) < 0.05  # one turn unwrapped
    assert (tmp_path / "writhe.png").stat().st_size > 1000
    assert scope["image"].shape == (480, 640, 3) and scope["image"].dtype == np.uint8
