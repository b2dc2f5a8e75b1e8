"""
Utilities for simple 1D and 2D static plots using matplotlib
"""

from .misc import *
from .cmap import *
from .image import *
from .curve import *
