"""matplotlib and tqdm are optional (the ``[plot]`` extra): import them, or say how to install them."""
from __future__ import annotations

from typing import Any

#: What to install for plots and progress bars.
INSTALL_HINT = 'pip install "dvoronoi[plot]"'


def require_matplotlib(caller: str = "plotting") -> Any:
    """Import matplotlib, or raise an ImportError that says how to install it."""
    try:
        import matplotlib
    except ImportError as e:
        raise ImportError(f"{caller} needs matplotlib, which is not installed: {INSTALL_HINT} "
                          "(or pip install matplotlib)") from e
    return matplotlib


def tqdm_class(required: bool) -> Any:
    """tqdm's bar class; None when tqdm is not installed and not `required` (a bar nobody asked for
    is left out), else an ImportError that says how to install it."""
    try:
        from tqdm.auto import tqdm
    except ImportError as e:
        if required:
            raise ImportError(f"progress=True needs tqdm, which is not installed: {INSTALL_HINT} "
                              "(or pip install tqdm)") from e
        return None
    return tqdm
