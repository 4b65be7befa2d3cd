"""scikit-sundae's IDA, imported without the 0.2-0.3 s of scipy it does not need here.

scikit-sundae's compiled modules run ``from scipy import sparse`` and ``from
scipy.optimize._numdiff import group_columns`` at import. The first (0.1 s: scipy.sparse and
its array-API layer) serves only a sparse linear solver's pattern; the second imports all of
scipy.optimize (and scipy.fft, scipy.linalg with it, 0.2 s) for the column grouping of a
finite-difference Jacobian, which never runs because circuitsim always hands IDA its own.
While scikit-sundae is imported, stand-ins answer for the two modules: scipy.sparse as a
:class:`~circuitsim.lazy.LazyModule` (imported at its first use, e.g. by a large model's sparse
solver) and ``_numdiff`` as a module whose ``group_columns`` imports the real one if called.
Both are then taken out of ``sys.modules``, so a later import of either is the ordinary one.
"""

from __future__ import annotations

import sys
import types
from typing import Any

from circuitsim.lazy import LazyModule


def _group_columns(A: Any, order: int = 0) -> Any:
    """scipy's column grouping, imported on first use (never, with our own Jacobians)."""
    from scipy.optimize._numdiff import group_columns

    return group_columns(A, order)


def _stand_ins() -> dict[str, Any]:
    numdiff = types.ModuleType("scipy.optimize._numdiff")
    numdiff.group_columns = _group_columns  # type: ignore[attr-defined]
    return {"scipy.sparse": LazyModule("scipy.sparse"), "scipy.optimize._numdiff": numdiff}


def ida_class() -> type:
    """``sksundae.ida.IDA``, imported lean on first use."""
    if "sksundae.ida" not in sys.modules:
        placed = {name: mod for name, mod in _stand_ins().items() if name not in sys.modules}
        sys.modules.update(placed)
        try:
            import sksundae.ida  # binds the stand-ins
        finally:
            for name, mod in placed.items():
                if sys.modules.get(name) is mod:
                    del sys.modules[name]
    import sksundae.ida

    return sksundae.ida.IDA


def ida_messages() -> dict[int, str]:
    """scikit-sundae's texts of IDA's return flags (the same words whichever route ran)."""
    ida_class()
    return dict(sys.modules["sksundae._cy_ida"].IDAMESSAGES)
