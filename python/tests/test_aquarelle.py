"""pytest suite of the `aquarelle` Python module (run by ctest as python.pytest).

Small sizes and few frames, so the whole file runs in seconds on llvmpipe."""
import os
import pathlib

import numpy as np
import pytest

import aquarelle

SOURCE = pathlib.Path(os.environ.get("AQ_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
UNDERWATER = str(SOURCE / "graphs" / "underwater.json")


@pytest.fixture(scope="module")
def renderer():
    return aquarelle.Renderer(gl="egl")


def small(path=UNDERWATER, width=64, height=36):
    graph = aquarelle.Graph.load(path)
    graph.width, graph.height = width, height
    graph.quality = "final"
    graph.precision = "float"
    return graph


def test_node_types_list_ports_and_params():
    types = {t.name: t for t in aquarelle.node_types()}
    assert {"scene", "gbuffer", "blur", "tint", "cel_light"} <= set(types)
    gbuffer = types["gbuffer"]
    assert [p.name for p in gbuffer.outputs] == [
        "position", "normal", "albedo", "depth", "id", "surface"]
    assert gbuffer.inputs[0].type == "scene"
    blur = aquarelle.node_type("blur")
    sigma = {p.name: p for p in blur.params}["sigma"]
    assert sigma.type == "float" and sigma.min <= sigma.default <= sigma.max
    with pytest.raises(aquarelle.Error, match="unknown node type 'blurr'.*installed: .*blur"):
        aquarelle.node_type("blurr")


def test_problems_are_objects_with_file_line_node_and_parameter(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text(
        '{\n  "aquarelle": 1,\n  "nodes": {\n'
        '    "s": {"type": "scene"},\n'
        '    "g": {"type": "gbuffer", "inputs": {"scene": "s.scene"}},\n'
        '    "b": {"type": "blur", "params": {"sigma": "wide"},\n'
        '          "inputs": {"image": "g.albedo", "depth": "g.depth"}}\n'
        "  },\n"
        '  "output": "b.image"\n}\n'
    )
    problems = aquarelle.validate_file(str(bad))
    assert len(problems) == 1
    p = problems[0]
    assert (p.file, p.line, p.node, p.parameter) == (str(bad), 6, "b", "sigma")
    assert "number" in p.message and "wide" in p.message
    assert str(p).startswith(f"{bad}:6:")
    with pytest.raises(aquarelle.GraphError) as raised:
        aquarelle.Graph.load(str(bad))
    assert raised.value.problems[0].parameter == "sigma"
    assert isinstance(raised.value, aquarelle.Error) and isinstance(raised.value, RuntimeError)
    assert aquarelle.validate_file(UNDERWATER) == []


def test_parameters_and_links_are_edited_with_the_command_lines_checks():
    graph = aquarelle.Graph.load(UNDERWATER)
    assert graph.nodes["gbuf"] == "gbuffer"
    assert graph.inputs("light")["surface"] == "gbuf.surface"
    graph.set("blur", "sigma", 1.5)
    assert graph.get("blur", "sigma") == 1.5
    assert graph.params("blur")["sigma"] == 1.5
    with pytest.raises(aquarelle.Error, match="has no parameter 'sigmaa' \\(parameters: "):
        graph.set("blur", "sigmaa", 1.0)
    with pytest.raises(aquarelle.Error, match="no node 'blurr'"):
        graph.set("blurr", "sigma", 1.0)
    with pytest.raises(aquarelle.GraphError) as raised:
        graph.set("blur", "sigma", "wide")
    assert raised.value.problems[0].node == "blur"
    assert graph.get("blur", "sigma") == 1.5  # a refused value leaves the old one
    graph.unlink("vignette.image")
    assert graph.problems() and graph.problems()[0].node == "vignette"
    graph.link("blur.image", "vignette.image")
    assert graph.problems() == []
    with pytest.raises(aquarelle.GraphError, match="cycle"):
        graph.link("tint.image", "blur.image")
    assert graph.problems() == []
    with pytest.raises(aquarelle.Error, match="has no input 'imag'"):
        graph.link("blur.image", "vignette.imag")


def test_saved_graph_reads_back_the_same(tmp_path):
    graph = aquarelle.Graph.load(UNDERWATER)
    graph.set("tint", "amount", 0.5)
    graph.save(str(tmp_path / "copy.json"))
    again = aquarelle.Graph.load(str(tmp_path / "copy.json"))
    assert again.get("tint", "amount") == 0.5
    assert again.to_json() == graph.to_json()


def test_any_node_output_is_a_float32_array_with_row_0_at_the_top(renderer):
    graph = small()
    image = renderer.evaluate(graph, frame=3)
    assert image.dtype == np.float32 and image.shape == (36, 64, 4)
    assert np.isfinite(image).all() and image[..., :3].std() > 0.01
    normal = renderer.evaluate(graph, frame=3, output="gbuf.normal")
    assert normal.shape == (36, 64, 4)
    lengths = np.linalg.norm(normal[..., :3], axis=2)
    assert abs(lengths.max() - 1.0) < 1e-2
    position = renderer.evaluate(graph, frame=3, output="gbuf.position")
    # The camera looks over the sea floor: the bottom of the picture is floor, the top open
    # water (no geometry, position 0). Row 0 must be the top.
    def covered(row):
        return (np.abs(row[:, :3]).sum(axis=1) > 0).mean()

    assert covered(position[-1]) > 0.9 and covered(position[0]) < 0.5
    depth = renderer.evaluate(graph, frame=3, output="gbuf.depth")
    assert (depth[..., 0] == depth[..., 1]).all() and (depth[..., 3] == 1).all()


def test_the_array_matches_the_command_lines_frame(renderer, tmp_path):
    graph = small()
    written = renderer.render(graph, str(tmp_path / "py.####.exr"), frames=(4, 4))
    assert written == 1
    from_file = aquarelle.read_image(str(tmp_path / "py.0004.exr"))
    evaluated = renderer.evaluate(graph, frame=4)
    assert np.abs(from_file - evaluated).max() < 2e-3  # the file is half float


def test_a_parameter_change_changes_the_output(renderer):
    graph = small()
    before = renderer.evaluate(graph, frame=1)
    graph.set("tint", "amount", 0.0)
    after = renderer.evaluate(graph, frame=1)
    assert np.abs(before - after).max() > 0.01


def test_a_bypassed_node_passes_its_input_through(renderer, tmp_path):
    graph = small()
    before_tint = renderer.evaluate(graph, frame=2, output="vignette.image")
    graph.set_bypass("tint")
    assert graph.bypass("tint") and not graph.bypass("vignette")
    bypassed = renderer.evaluate(graph, frame=2)
    assert np.array_equal(bypassed, before_tint)
    graph.save(str(tmp_path / "bypassed.json"))
    assert aquarelle.Graph.load(str(tmp_path / "bypassed.json")).bypass("tint")
    graph.set_bypass("tint", False)
    assert np.abs(renderer.evaluate(graph, frame=2) - before_tint).max() > 0.01


def test_render_a_range_with_progress_and_resume(renderer, tmp_path):
    graph = small(width=48, height=27)
    calls = []
    out = str(tmp_path / "f.####.png")
    written = renderer.render(graph, out, frames=(1, 3), progress=lambda *a: calls.append(a))
    assert written == 3
    assert calls == [(1, 1, 3), (2, 2, 3), (3, 3, 3)]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.0001.png", "f.0002.png", "f.0003.png"]
    (tmp_path / "f.0002.png").unlink()
    assert renderer.render(graph, out, frames=(1, 3), resume=True) == 1
    with pytest.raises(aquarelle.Error, match="needs `####` in the output name"):
        renderer.render(graph, str(tmp_path / "one.png"), frames=(1, 3))


def test_errors_carry_the_command_lines_messages(renderer, tmp_path):
    graph = small()
    with pytest.raises(aquarelle.Error, match="output folder '.*missing' does not exist"):
        renderer.render(graph, str(tmp_path / "missing" / "####.exr"), frames=(1, 2))
    with pytest.raises(aquarelle.Error, match="frame 2: .*no output port 'nope'"):
        renderer.evaluate(graph, frame=2, output="gbuf.nope")
    graph.set("scene", "path", str(tmp_path / "absent.obj"))
    graph.set("scene", "preset", "file")
    with pytest.raises(aquarelle.Error, match="node 'scene'"):
        renderer.evaluate(graph, frame=1)


def test_write_and_read_images(tmp_path):
    pixels = np.zeros((8, 16, 4), np.float32)
    pixels[0, :, 0] = 1.0  # a red top row
    pixels[..., 3] = 1.0
    aquarelle.write_image(str(tmp_path / "a.exr"), pixels)
    back = aquarelle.read_image(str(tmp_path / "a.exr"))
    assert back.shape == (8, 16, 4)
    assert (back[0, :, 0] == 1).all() and (back[1:, :, 0] == 0).all()
    with pytest.raises(aquarelle.Error, match="shape"):
        aquarelle.write_image(str(tmp_path / "b.exr"), np.zeros((4, 4, 2), np.float32))
