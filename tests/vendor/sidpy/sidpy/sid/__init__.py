"""
Spectroscopy and Imaging Data related classes
"""

from .dimension import Dimension, DimensionType
from .translator import Translator
from .dataset import Dataset, DataType, convert_hyperspy
from .reader import Reader

__all__ = ['Dimension', 'DimensionType', 'Dataset', 'DataType', 'Reader',
           'Translator', 'convert_hyperspy']
