"""
User interface utilities
"""
from . import interface_utils
from .interface_utils  import FileWidget, ChooseDataset
__all__ = ['interface_utils', 'FileWidget', 'ChooseDataset']
