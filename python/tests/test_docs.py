"""The examples of docs/python.md and docs/gis.md run as written: the Python
blocks of a page in order in one namespace, the shell blocks with bash, in a
scratch folder, with DATA the shared data folder and `overflight` on PATH."""
import os
import re
import subprocess
import sys

import pytest

DOCS = os.path.join(os.path.dirname(__file__), "..", "..", "docs")


def blocks(page, language):
    with open(os.path.join(DOCS, page)) as f:
        return re.findall(r"```" + language + r"\n(.*?)```", f.read(), re.S)


@pytest.fixture
def doc_env(tmp_path, shared_file, overflight_exe, monkeypatch):
    data = os.path.dirname(os.path.dirname(shared_file("srtm/mt_rainier_90m.tif")))
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("DATA", data)
    exe_dir = os.path.dirname(os.path.abspath(overflight_exe))
    monkeypatch.setenv("PATH", exe_dir + os.pathsep + os.environ["PATH"])
    return tmp_path


def test_python_md_runs(doc_env, capsys):
    code = blocks("python.md", "python")
    assert len(code) >= 4
    namespace = {"__name__": "docs"}
    for block in code:
        exec(compile(block, "docs/python.md", "exec"), namespace)
    out = capsys.readouterr().out
    assert "(540, 960, 3) uint8 (540, 960) float32" in out
    assert out.count("frame ") == 8
    assert (doc_env / "path_7.png").exists() and (doc_env / "paradise.png").exists()


def test_gis_md_runs(doc_env):
    code = blocks("gis.md", "sh")
    assert len(code) >= 3
    for block in code:
        r = subprocess.run(["bash", "-euo", "pipefail", "-c", block], capture_output=True, text=True)
        assert r.returncode == 0, block + r.stderr
    assert (doc_env / "paradise.json").exists()
    for png in ("paradise.png", "paradise_mesh.png", "paradise_small.png"):
        assert (doc_env / png).exists()
