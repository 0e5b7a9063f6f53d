"""``irnuc mutate`` on several configurations: a mutant runs only where its code
elaborates to another design (``irnuc.verif.mutate.elaborates_differently``)."""

from __future__ import annotations

import pytest

from irnuc.nuc_fixed import load_pipeline
from irnuc.verif import mutate


@pytest.mark.cosim
def test_a_mutant_differs_only_where_its_branch_is_elaborated() -> None:
    """The half-up rounding mutant changes the design of a half_up configuration and
    not that of a truncate one (whose gen_inc_half_up block is not built); a mutant of
    always-built code changes both."""
    base = load_pipeline("minimal")
    assert base.frac_bits > 0
    half_up, truncate = base.replace(rounding="half_up"), base.replace(rounding="truncate")
    m = mutate.catalogue(["nuc_half_up_no_inc"])[0]
    assert mutate.elaborates_differently(m, half_up)
    assert not mutate.elaborates_differently(m, truncate)
    always = mutate.catalogue(["ctrl_flush_short"])[0]
    assert mutate.elaborates_differently(always, truncate)
