"""The per-frame readings a method or stage can take (``MethodSpec.readings``).

A reading is what a frame brings besides its pixels: the FPA sensor's reading (``fpa``,
tc_offset, tc_housing and table_interp), the housing sensor's reading (``housing``,
tc_housing), the blind pixels' codes (``blind``, blind_drift), the shutter
flag (``shutter``, ffc). A method declares the readings it takes by name; the frame file's
field, the golden model's :class:`~irnuc.nuc_fixed.method_top.FrameInputs` attribute, the
parameters and the runtime register each brings are written here once.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from irnuc.nuc_fixed.spec import ParamSpec, ReadingSpec, Register, RegisterSlot

if TYPE_CHECKING:
    from irnuc.nuc_fixed.config import PipelineConfig


def _fpa_register(cfg: PipelineConfig) -> Register:
    r = int(cfg.reading_bits or 1)
    return Register("reading", r, False, f"U{r}.0", source="runtime",
                    meaning="FPA sensor reading latched at the frame start")


def _housing_register(cfg: PipelineConfig) -> Register:
    r = int(cfg.housing_bits or 1)
    return Register("housing_reading", r, False, f"U{r}.0", source="runtime",
                    meaning="housing sensor reading latched at the frame start")


READINGS: dict[str, ReadingSpec] = {r.name: r for r in (
    ReadingSpec("fpa", "fpa_reading", "reading",
                "the FPA (substrate) sensor's reading, an unsigned code latched per frame",
                params=(ParamSpec.range("reading_bits", 1, 24, "bits",
                                        "bits of the FPA sensor's reading", "ReadingBits", 14),),
                register=_fpa_register,
                slot=RegisterSlot("ReadingRegBits", "reading", "ReadingBits")),
    ReadingSpec("housing", "housing_reading", "housing_reading",
                "the housing (lens, shutter) sensor's reading, an unsigned code latched per "
                "frame",
                params=(ParamSpec.range("housing_bits", 1, 24, "bits",
                                        "bits of the housing sensor's reading", "HousingBits",
                                        14),),
                register=_housing_register,
                slot=RegisterSlot("HousingReadingRegBits", "housing_reading", "HousingBits")),
    ReadingSpec("blind", "blind_codes", "blind_codes",
                "the codes of the frame's blind (reference) pixels"),
    ReadingSpec("shutter", "shutter", "shutter", "the shutter flag of the frame"),
)}
