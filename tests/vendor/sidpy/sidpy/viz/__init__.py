"""
Tools for static and interactive visualization of scientific imaging and
spectroscopy data

Submodules
----------

.. autosummary::
    :toctree: _autosummary

    plot_utils
    jupyter_utils
    dataset_viz
"""

from . import plot_utils, jupyter_utils, dataset_viz

__all__ = ['plot_utils', 'jupyter_utils', 'dataset_viz']
