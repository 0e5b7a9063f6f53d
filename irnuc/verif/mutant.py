"""One mutant of the RTL (a text change to one file) and where it runs: the catalogue
(:mod:`irnuc.verif.catalogue`) is made of them, :mod:`irnuc.verif.mutate` runs them."""

from __future__ import annotations

from dataclasses import dataclass

from irnuc.cocotb_tests import tb_pkg, tb_top
from irnuc.common.errors import UserError

#: The testbench module every mutant runs against.
SUITE_MODULE = tb_top.__name__
SUITE_TOP = "nuc_dpc_top"
#: A mutant of the package also runs the package check (every constant, width function and
#: the DPC reciprocal table against the shared-constants spec) after the suite passed.
PKG_FILE = "irnuc_pkg.sv"
PKG_TOP, PKG_SUITE = "irnuc_pkg_probe", tb_pkg.__name__


@dataclass(frozen=True)
class Mutant:
    """One change to one RTL file: ``find`` (occurring exactly once) becomes ``replace``."""

    id: str
    file: str
    find: str
    replace: str
    what: str
    #: configuration: a named pipeline and mode changes (the mutated code must be elaborated)
    config: str = "minimal"
    changes: tuple[tuple[str, str], ...] = ()
    #: why no test can kill it (then "equivalent" when it survives)
    equivalent: str | None = None
    #: further (find, replace) pairs in the same file, for a change at several sites
    also: tuple[tuple[str, str], ...] = ()
    #: the top and the testbench module of the mutant's suite (the methods' modules run in
    #: method_dpc_top with tb_method, interp_weight alone with its testbench)
    top: str = SUITE_TOP
    suite: str = SUITE_MODULE
    #: equivalent on some configurations only: (pipeline field, largest value, why), the
    #: mutant is equivalent on a configuration whose field is at most that value
    equivalent_when: tuple[tuple[str, int, str], ...] = ()
    #: an automatic mutant (irnuc.verif.automut): the Yosys ``mutate -mode ...`` command
    #: applied to the netlist of ``top`` on the mutant's configuration, which replaces the
    #: top's RTL (``find`` / ``replace`` unused); "" is the unmutated netlist
    yosys: str | None = None

    def equivalence(self, cfg=None) -> str | None:
        """Why no test can kill the mutant on ``cfg`` (a pipeline configuration; None: on
        every configuration), or None."""
        if self.equivalent or cfg is None:
            return self.equivalent
        for name, most, why in self.equivalent_when:
            if getattr(cfg, name) <= most:
                return f"{name} <= {most}: {why}"
        return None

    def apply(self, text: str) -> str:
        for find, replace in ((self.find, self.replace), *self.also):
            n = text.count(find)
            if n != 1:
                raise UserError(f"mutant {self.id}: the text to change occurs {n} times in "
                                f"{self.file} (expected once); update the catalogue")
            text = text.replace(find, replace)
        return text

    def pipeline(self):
        from irnuc.nuc_fixed import load_pipeline

        cfg = load_pipeline(self.config)
        if not self.changes:
            return cfg
        # ``formats`` changes are nested pairs: ((name, ((field, value), ...)), ...).
        ch = {k: ({n: dict(f) for n, f in v} if k == "formats" else v) for k, v in self.changes}
        return cfg.replace(**ch)


__all__ = ["PKG_FILE", "PKG_SUITE", "PKG_TOP", "SUITE_MODULE", "SUITE_TOP", "Mutant"]
