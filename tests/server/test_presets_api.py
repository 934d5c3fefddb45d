"""GET /api/v1/presets and POST /api/v1/presets/{name}: the listing, the OpenAPI documentation of
every parameter, and the round trip preset -> scene -> /analyze (issue 2, "Presets")."""

from fastapi.testclient import TestClient

from solver.teaching.presets import PRESETS


def test_listing_names_every_parameter_with_unit_default_and_bounds(client: TestClient) -> None:
    listing = client.get("/api/v1/presets").json()["presets"]
    assert [p["name"] for p in listing] == list(PRESETS)
    for preset in listing:
        for q in preset["parameters"]:
            assert {"name", "default", "unit", "description", "minimum", "maximum"} <= set(q)
            if q["choices"] is not None:
                assert q["labels"] is None or len(q["labels"]) == len(q["choices"])
    four_bar = next(p for p in listing if p["name"] == "four_bar")
    assembly = next(q for q in four_bar["parameters"] if q["name"] == "assembly")
    assert assembly["labels"] == ["open", "crossed"]


def test_openapi_documents_each_preset_parameter(client: TestClient) -> None:
    spec = client.get("/api/v1/openapi.json").json()
    schemas = spec["components"]["schemas"]
    for name, preset in PRESETS.items():
        assert f"/api/v1/presets/{name}" in spec["paths"]
        properties = schemas[f"{name}_parameters"]["properties"]
        assert set(properties) == {q.name for q in preset.parameters}


def test_every_preset_round_trips_through_analyze(client: TestClient) -> None:
    """The scene a preset returns is accepted by /analyze, which places every point where the
    preset drew it (to 1e-12 of the scene's size)."""
    for name in PRESETS:
        scene = client.post(f"/api/v1/presets/{name}", json={}).json()
        answer = client.post("/api/v1/analyze", json={"scene": scene, "quantities": ["position"]})
        assert answer.status_code == 200, answer.text
        xs = [c for xy in scene["points"].values() for c in xy]
        size = max(xs) - min(xs) + 1e-300
        for point, xy in scene["points"].items():
            got = answer.json()["points"][point]["position"]
            assert max(abs(got[0] - xy[0]), abs(got[1] - xy[1])) <= 1e-12 * size, (name, point)


def test_the_listing_carries_each_preset_scene_at_its_defaults(client: TestClient) -> None:
    """Every family's listing gives each preset's ``scene``: exactly what POST /presets/{name}
    with {} answers (the app opens a preset at its defaults from it, without a request)."""
    for family in ("linkages", "cams", "gear_trains"):
        listing = client.get("/api/v1/presets", params={"family": family}).json()["presets"]
        assert listing, family
        for preset in listing:
            built = client.post(f"/api/v1/presets/{preset['name']}", json={})
            assert built.status_code == 200, built.text
            assert preset["scene"] == built.json(), preset["name"]
