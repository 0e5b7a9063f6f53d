"""Work-precision measurements of every numerical method of the model.

For each component, every method is run over a range of settings (series tolerance or
terms, Newton tolerance or iteration cap, integrator steps or tolerance). A point is the
error (max relative over the sample, against an independent reference), the run time
(minimum of a few runs after an untimed warm-up call, which compiles every kernel and
signature the setting reaches: JIT compilation is never on the time axis) and the work
(series terms, Newton iterations or integrator substeps: a second axis free of timing
noise). A method that fails at a setting (an error, a solver status other than OK, a
non-finite value) is a failed point with its reason and the time a second (compiled) call
took to fail. The
default setting of each component is marked and checked against the Pareto front.

References, all independent of the code under test and kept as double-double values (a
float64 pair) so that errors far below float64 resolution stay measurable:

* band radiance: the tail series summed in mpmath at 80 digits (no underflow);
* electro-thermal solve: mpmath ``findroot`` at 40 digits per sampled pixel;
* transient: every pulse by quadrature in the phase variable at 60 digits
  (:func:`reference_transient_exact`), the relaxations in closed form. scipy's Radau
  (:func:`reference_transient`) agrees to ~1e-15 and is the tests' second opinion.

Each component reports its reference's own error estimate (the same reference at fewer
digits); it is many orders of magnitude below every plotted error.

Stable API for reports: :func:`run_precision` (JSON-ready dict), :func:`figures`
(caption, PNG bytes) and :func:`summarize` (compact metrics).

Modules: :mod:`.harness` (timing, points, the Pareto front), :mod:`.references` (mpmath and
scipy references), :mod:`.studies` (the components and the run), :mod:`.figures`.
"""

from irnuc.reports.studies.precision.figures import failure_label, figure_png, figures
from irnuc.reports.studies.precision.harness import (
    ERROR_FLOOR,
    ERROR_MARGIN,
    TIME_BUDGET,
    TIME_MARGIN,
    TRANSIENT_BUDGET,
    Point,
    SettingFailed,
    best_time,
    dominates,
    mark_front,
    rel_error_dd,
    single_thread,
)
from irnuc.reports.studies.precision.references import (
    REFERENCE_DPS,
    band_radiance_mp,
    band_radiance_quad_mp,
    reference_transient,
    reference_transient_exact,
    tail_integral_mp,
)
from irnuc.reports.studies.precision.studies import (
    COMPONENTS,
    GROUPS,
    NARROW_BAND,
    TRANSIENT_PROBLEMS,
    component_names,
    run_precision,
    summarize,
    transient_problem,
)

__all__ = [
    "COMPONENTS", "ERROR_FLOOR", "ERROR_MARGIN", "GROUPS", "NARROW_BAND", "REFERENCE_DPS",
    "TIME_BUDGET", "TIME_MARGIN", "TRANSIENT_BUDGET", "TRANSIENT_PROBLEMS", "Point",
    "SettingFailed", "band_radiance_mp", "band_radiance_quad_mp", "best_time",
    "component_names", "dominates", "failure_label", "figure_png", "figures", "mark_front",
    "reference_transient", "reference_transient_exact", "rel_error_dd", "run_precision",
    "single_thread", "summarize", "tail_integral_mp", "transient_problem",
]
