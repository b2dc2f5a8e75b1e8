"""
Basic computational utilities
"""

from . import fitter

__all__ = ['fitter']
