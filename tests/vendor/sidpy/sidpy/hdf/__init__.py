"""
Tools to read, write data in HDF5 files
"""
from . import hdf_utils, prov_utils, reg_ref, dtype_utils

__all__ = ['hdf_utils', 'prov_utils', 'reg_ref', 'dtype_utils']
