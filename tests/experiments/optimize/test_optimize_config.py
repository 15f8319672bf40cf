"""The optimisation config: every field checked, the error names it and its range."""

import pytest

from experiments.optimize.config import OptimizeConfigError, config_from_dict, load_config

GOOD = {
    "name": "t",
    "objective": {"trials": 4, "seed": 0},
    "methods": [{"method": "differential-evolution", "budget": 10, "seeds": [0, 1]}],
}


def with_(**changes):
    return {**GOOD, **changes}


def test_the_shipped_configs_load():
    for name in ("optimize", "optimize-compare"):
        config = load_config(name)
        assert config.methods and config.trials >= 1


@pytest.mark.parametrize(
    "data, words",
    [
        (with_(methods=[{"method": "fmincon", "budget": 5}]), ["methods[0].method", "nelder-mead"]),
        (with_(methods=[{"method": "powell", "budget": 0}]), ["methods[0].budget", "[1,"]),
        (with_(methods=[{"method": "powell"}]), ["methods[0].budget", "required"]),
        (with_(methods=[{"method": "powell", "budget": 5, "seeds": [1, 1]}]), ["seed twice"]),
        (with_(methods=[{"method": "powell", "budget": 5, "population": 2}]), ["population"]),
        (with_(methods=[]), ["methods"]),
        (
            with_(methods=[{"method": "powell", "budget": 5, "start": "anywhere"}]),
            ["start", "best"],
        ),
        (
            with_(methods=[{"method": "powell", "budget": 5}, {"method": "powell", "budget": 9}]),
            ["twice"],
        ),
        (with_(objective={"trials": 0}), ["objective.trials", "[1,"]),
        (with_(objective={"weight": -1}), ["objective.weight"]),
        (with_(objective={"step": 1.0}), ["objective.step"]),
        (with_(start={"presets": ["fig99"]}), ["start.presets[0]", "table3"]),
        (with_(final={"trials": 0}), ["final.trials"]),
        (with_(final={"target": 1.5}), ["final.target"]),
        (with_(perturbations={"yaw": 2.0}), ["perturbations.yaw", "allowed range"]),
        (with_(feeder={"friction": -1}), ["feeder.friction"]),
        (with_(colour="red"), ["unknown key", "colour"]),
        ("not a mapping", ["config", "mapping"]),
    ],
)
def test_bad_input_names_the_field(data, words):
    with pytest.raises(OptimizeConfigError) as info:
        config_from_dict(data)
    for word in words:
        assert word in str(info.value)


def test_the_objective_key_ignores_methods_and_workers_but_not_the_draws():
    a = config_from_dict(GOOD)
    b = config_from_dict(with_(workers=1, methods=[{"method": "powell", "budget": 3}]))
    c = config_from_dict(with_(objective={"trials": 4, "seed": 1}))
    assert a.objective_key() == b.objective_key()
    assert a.objective_key() != c.objective_key()
