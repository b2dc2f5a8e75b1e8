"""
General python helper functions
"""

from . import num_utils, string_utils, dict_utils

__all__ = ['num_utils', 'string_utils', 'dict_utils']
