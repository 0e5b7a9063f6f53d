"""Float physics model of an uncooled microbolometer sensor (Leja et al., Sensors 2022).

Public API::

    from irnuc import model
    cfg = model.load_preset("default", overrides={"fpa.active_rows": 48})
    frames = model.simulate(cfg, temps=[300, 350, 400], scene="uniform", seed=1)
    frames.codes  # (3, 48, W) uint16

    seq = model.load_sequence("drift.toml")       # docs/sequences.md
    drift = model.simulate_sequence(cfg, seq, seed=1)
    drift.codes, drift.blind_codes, drift.fields["fpa_reading"]
    model.netd(cfg, 300.0)                        # closed-form NETD, K (docs/model.md)
"""

from irnuc.common.errors import ConfigError
from irnuc.model.config import load_config, load_preset, preset_names
from irnuc.model.defects import DefectKind, DefectPattern
from irnuc.model.noise_metrics import netd, noise_3d, responsivity
from irnuc.model.optics import cone_factor, cos4_map
from irnuc.model.pipeline import OUTPUTS, Frames, Pipeline, simulate
from irnuc.model.radiometry import BAND_RADIANCE_METHODS, band_radiance
from irnuc.model.scenes import Scene
from irnuc.model.sequence import (
    load_sequence,
    prepare_sequence,
    sequence_from_dict,
    simulate_sequence,
    write_sequence,
)

__all__ = [
    "BAND_RADIANCE_METHODS",
    "OUTPUTS",
    "ConfigError",
    "DefectKind",
    "DefectPattern",
    "Frames",
    "Pipeline",
    "Scene",
    "band_radiance",
    "cone_factor",
    "cos4_map",
    "load_config",
    "load_preset",
    "load_sequence",
    "netd",
    "noise_3d",
    "prepare_sequence",
    "preset_names",
    "responsivity",
    "sequence_from_dict",
    "simulate",
    "simulate_sequence",
    "write_sequence",
]
