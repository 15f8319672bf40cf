"""A trial's outcome does not depend on how the made feeder and its level are computed
(issue 21, "the cost of a trial"): the verdict trials of three presets with seed 21, as
recorded before the toleranced build and the cover split were made cheaper, drop for drop.

Each row is one trial: per entry, success, outcome class, exit time T (s) and the final
distance to the goal (Eq. 10), the floats as ``float.hex`` so that equality is bitwise. A
drop through a feeder is chaotic (a 1e-16 change of one wall vertex changes its end), so the
final distances would show any change of the walls, the split or the corners.
"""

from __future__ import annotations

import pytest

from experiments.drop.verdict import made_feeders, run_trial
from experiments.drop.verdict_settings import VerdictSettings
from feeders.design import preset
from feeders.feeder import ORIENTATIONS

SEED = 21
RECORDED = {
    "table3": (
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.2c28f5c28f5c3p+1", "0x1.19ba5e353f7cfp+1"),
            ("0x1.80951ea3e8fdap-3", "0x1.9de0dbc7d9a7ap-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.34dd2f1a9fbe8p+1", "0x1.183126e978d50p+1"),
            ("0x1.290655fe2e62bp-3", "0x1.7994e73eb23f1p-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.24395810624ddp+1", "0x1.16e978d4fdf3bp+1"),
            ("0x1.6a124c6d5bdd6p-3", "0x1.8f9f717f61046p-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.3b851eb851eb8p+1", "0x1.1a1cac083126fp+1"),
            ("0x1.99c787a1cd7a0p-5", "0x1.a481b46c583f7p-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.23b645a1cac08p+1", "0x1.1374bc6a7ef9ep+1"),
            ("0x1.0aaba08283411p-3", "0x1.a7f33aec230cbp-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.3ac083126e979p+1", "0x1.151eb851eb852p+1"),
            ("0x1.d7861cf57f42ep-4", "0x1.af0dd2dbeda2dp-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.36e978d4fdf3cp+1", "0x1.176c8b4395810p+1"),
            ("0x1.d8a75236ce194p-6", "0x1.a84371e5f7e40p-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.3810624dd2f1bp+1", "0x1.147ae147ae148p+1"),
            ("0x1.d645d12408af4p-4", "0x1.961d60453735bp-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.2395810624dd3p+1", "0x1.15a1cac083127p+1"),
            ("0x1.ca12368d8dfa1p-4", "0x1.a2e8a99dc8095p-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.2c6a7ef9db22dp+1", "0x1.15810624dd2f2p+1"),
            ("0x1.7910b4c967ad8p-3", "0x1.880a51787f6a6p-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.30a3d70a3d70ap+1", "0x1.1666666666667p+1"),
            ("0x1.d2592740a1bd9p-4", "0x1.9dd765d25ed72p-3"),
        ),
        (
            (True, True),
            ("heavy end down", "heavy end down"),
            ("0x1.36e978d4fdf3cp+1", "0x1.178d4fdf3b646p+1"),
            ("0x1.074c9ab63995ap-5", "0x1.8e5c2f596dc07p-3"),
        ),
    ),
    "fig9": (
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.d53f7ced91687p+0", "0x1.ee978d4fdf3b6p+0"),
            ("0x1.8434c065e2496p-3", "0x1.93f867ea68c0bp+1"),
        ),
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.ce147ae147ae1p+0", "0x1.e83126e978d50p+0"),
            ("0x1.6e9c7c2fbac6bp-3", "0x1.93e322ad15562p+1"),
        ),
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.d0a3d70a3d70ap+0", "0x1.eac083126e979p+0"),
            ("0x1.52e643d812bfdp-3", "0x1.93fdbf2b020dfp+1"),
        ),
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.d5c28f5c28f5cp+0", "0x1.ee978d4fdf3b6p+0"),
            ("0x1.7d68ccf06bbf8p-3", "0x1.9404bbd8dc120p+1"),
        ),
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.d26e978d4fdf4p+0", "0x1.e978d4fdf3b65p+0"),
            ("0x1.792e35dd9b701p-3", "0x1.940660c5001fap+1"),
        ),
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.d22d0e5604189p+0", "0x1.eb851eb851eb8p+0"),
            ("0x1.410ce432beeadp-3", "0x1.9400f0ea739bap+1"),
        ),
    ),
    "fig5b": (
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.1020c49ba5e35p+1", "0x1.3d916872b020cp+1"),
            ("0x1.d369daf3150b5p-4", "0x1.8aabccf03ed6fp+1"),
        ),
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.10624dd2f1aa0p+1", "0x1.1ef9db22d0e56p+1"),
            ("0x1.0a4c87e3e08d2p-3", "0x1.92ef71bdf30a7p+1"),
        ),
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.1020c49ba5e35p+1", "0x1.27ced916872b0p+1"),
            ("0x1.30fcc448b8241p-3", "0x1.8d5e3176f52ecp+1"),
        ),
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.1126e978d4fdfp+1", "0x1.3e76c8b439581p+1"),
            ("0x1.06a253b7423d4p-3", "0x1.88cbdb1688539p+1"),
        ),
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.0d916872b020cp+1", "0x1.67ced916872b0p+1"),
            ("0x1.e509a116f38b2p-4", "0x1.9304151d050e6p+1"),
        ),
        (
            (True, False),
            ("heavy end down", "heavy end up"),
            ("0x1.16872b020c49cp+1", "0x1.549ba5e353f7dp+1"),
            ("0x1.8732723003ed8p-3", "0x1.9250572a6f34fp+1"),
        ),
    ),
}


@pytest.mark.parametrize("name", sorted(RECORDED))
def test_verdict_trials_are_the_recorded_ones_bit_for_bit(name: str) -> None:
    """Trial i of the verdict with ``SEED`` (what ``design_verdict`` runs as its i-th trial,
    whatever its stopping rule) is the recorded row i."""
    rows = RECORDED[name]
    make_scene = made_feeders(preset(name))
    settings = VerdictSettings()
    for index, (success, outcome, times, errors) in enumerate(rows):
        trial = run_trial(make_scene, ORIENTATIONS, settings, SEED, index)
        assert trial.success == success, f"{name} trial {trial.index}"
        assert trial.outcome == outcome, f"{name} trial {trial.index}"
        assert tuple(float.hex(t) for t in trial.T) == times, f"{name} trial {trial.index}"
        assert tuple(float.hex(e) for e in trial.goal_error) == errors, (
            f"{name} trial {trial.index}"
        )
