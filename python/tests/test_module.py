"""The Python module against the command line (DESIGN sec. 6.1): the same view
gives the same arrays as `overflight render`'s PNG and depth TIFF; NumPy
height arrays render; errors are overflight.Error with the command line's
one-line message; two threads render at once."""
import threading

import numpy as np
import pytest
from osgeo import gdal

import overflight

gdal.UseExceptions()


def read_png(path):
    return np.transpose(gdal.Open(str(path)).ReadAsArray(), (1, 2, 0))


def read_depth(path):
    return gdal.Open(str(path)).ReadAsArray()


def cli_render(run_cli, tmp_path, terrain, method, args):
    png, tif = tmp_path / (method + ".png"), tmp_path / (method + ".tif")
    r = run_cli("render", terrain, "--method", method, "-o", png, "--depth", tif, *args)
    assert r.returncode == 0, r.stderr
    return read_png(png), read_depth(tif)


@pytest.mark.parametrize("method", ["voxel", "mesh"])
def test_arrays_equal_the_cli_outputs(run_cli, tmp_path, method):
    t = overflight.load("demo", demo_size=257)
    color, depth = overflight.render(t, method, (96, 64), at=(1300, 1900), agl=37.5, heading=33.3, pitch=-7.25,
                                     projection="tilt")
    assert color.shape == (64, 96, 3) and color.dtype == np.uint8
    assert depth.shape == (64, 96) and depth.dtype == np.float32
    cli_color, cli_depth = cli_render(run_cli, tmp_path, "demo", method,
                                      ["--demo-size", 257, "--size", "96x64", "--at", "1300,1900", "--agl", 37.5,
                                       "--heading", 33.3, "--pitch", -7.25, "--projection", "tilt"])
    np.testing.assert_array_equal(color, cli_color)
    np.testing.assert_array_equal(depth, cli_depth)


def test_camera_file_and_dict_round_trip(tmp_path):
    t = overflight.load("demo", demo_size=129)
    saved = tmp_path / "view.json"
    a = overflight.render(t, size=(48, 32), at="600,700", heading=120, save_camera=str(saved))
    b = overflight.render(t, camera=saved)
    cam = overflight.camera(t, camera=str(saved))
    c = overflight.render(t, camera=cam)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)
    for x, y in zip(a, c):
        np.testing.assert_array_equal(x, y)
    assert cam["width"] == 48 and cam["heading"] == 120.0


def test_a_numpy_height_array_renders():
    # A 9x9 pyramid, 10 m cells, peak 40 m at the centre.
    i = np.arange(9)
    heights = 40.0 - 10.0 * np.maximum(abs(i[:, None] - 4), abs(i[None, :] - 4))
    t = overflight.from_array(heights, 10.0)
    assert (t.rows, t.cols, t.cell_size) == (9, 9, 10.0)
    np.testing.assert_allclose(t.heights(), heights, atol=1e-3)
    # From beyond the south edge, above the peak, looking down at its top.
    color, depth = overflight.render(t, size=(41, 31), eye=(40, 60, 140), look_at=(40, 40))
    assert depth[15, 20] < 1.0  # the peak is on the centre pixel
    assert (depth[0] == 1.0).all()  # sky above
    colors = np.zeros((9, 9, 3), np.uint8)
    colors[..., 0] = 200
    t2 = overflight.from_array(heights.astype(np.int16), 10.0, colors=colors)
    assert (t2.colors()[..., 0] == 200).all()


def test_a_bad_path_raises_the_cli_message(run_cli, tmp_path):
    missing = str(tmp_path / "nope.tif")
    with pytest.raises(overflight.Error) as e:
        overflight.load(missing)
    r = run_cli("render", missing, "-o", tmp_path / "x.png")
    assert r.returncode == 1
    assert r.stderr == "overflight: " + str(e.value) + "\n"
    assert str(e.value).startswith(missing + ": ")


def test_view_errors_name_the_option():
    t = overflight.load("demo", demo_size=65)
    with pytest.raises(overflight.Error, match=r"^--fov: 200 is outside \(0, 180\) degrees$"):
        overflight.render(t, size=(8, 8), fov=200)
    with pytest.raises(overflight.Error, match="--look-at: the terrain demo has no georeferencing"):
        overflight.render(t, size=(8, 8), look_at="lonlat:1,2")
    with pytest.raises(overflight.Error, match="--warp"):
        overflight.render(t, size=(8, 8), warp=3)
    with pytest.raises(overflight.Error, match="^heights: "):
        overflight.from_array(np.zeros(5), 1.0)


def test_two_threads_render_at_once():
    demo = overflight.load("demo", demo_size=129)
    other = overflight.load("demo", demo_size=129)
    expected = {m: overflight.render(demo, m, (64, 40))[0] for m in ("voxel", "mesh")}
    results, errors = [], []

    def work(terrain, method):
        try:
            for _ in range(4):
                results.append((method, overflight.render(terrain, method, (64, 40))[0]))
        except Exception as e:  # reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=a) for a in
               [(demo, "voxel"), (demo, "mesh"), (other, "voxel"), (other, "mesh")]]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert not errors
    assert len(results) == 16
    for method, color in results:
        np.testing.assert_array_equal(color, expected[method])


def test_sim_matches_the_cli(run_cli):
    t = overflight.load("demo", demo_size=257)
    rows = overflight.sim(t, steps=20, at=(1000, 1200), heading=90, press=["accelerate:0-20"])
    r = run_cli("sim", "demo", "--demo-size", 257, "--steps", 20, "--at", "1000,1200", "--heading", 90,
                "--press", "accelerate:0-20")
    assert r.returncode == 0, r.stderr
    cli = np.loadtxt(r.stdout.splitlines()[1:], delimiter=",")
    for k, name in enumerate(["step", "x", "z", "y", "velocity", "heading"]):
        np.testing.assert_allclose(rows[name], cli[:, k], atol=1e-6)
