# SPDX-License-Identifier: GPL-3.0-or-later
"""The one place in Python that opens shockgas's HDF5 files (h5py), as sim/io/include/shockgas/io/h5.hpp is
in C++: opening with the schema check, attribute decoding, and a generic tree of groups."""
import contextlib
import errno
import os
import re

import h5py
import numpy as np

from .schema import check_schema_version


def decode(value):
    """An HDF5 attribute as Python: text as str (h5py gives fixed-length strings as bytes), arrays of
    text as lists of str, numeric scalars as int/float, numeric arrays as numpy arrays."""
    if isinstance(value, (bytes, np.bytes_)):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "SO":
            return [decode(v) for v in value.tolist()]
        if value.shape == ():
            return value.item()
        return value
    if isinstance(value, np.generic):
        return value.item()
    return value


def decode_attributes(obj):
    return {name: decode(obj.attrs[name]) for name in obj.attrs}


class DamagedFile(OSError):
    """The file cannot be trusted: it is truncated, or data or metadata fail their checksum (files of
    schema_version 2 and later carry HDF5's Fletcher32 checksum on every dataset, which HDF5 checks on read)."""


def read_dataset(path, dataset):
    """A dataset's whole value; a read that fails (a checksum mismatch) raises DamagedFile naming both."""
    try:
        return dataset[()]
    except OSError as error:
        raise DamagedFile(f"{path}: damaged: dataset {dataset.name} cannot be read ({error})") from None


class _PathMessage:
    """str() as the module's other errors: "<path>: <what>" (errno and filename are kept)."""

    def __str__(self):
        return f"{self.filename}: {self.strerror}"


class NoSuchFile(_PathMessage, FileNotFoundError):
    """The path does not exist (a FileNotFoundError): "<path>: no such file (it does not exist)"."""


class _IsADirectory(_PathMessage, IsADirectoryError):
    pass


class _NotReadable(_PathMessage, PermissionError):
    pass


def _no_such_file(path):
    return NoSuchFile(errno.ENOENT, "no such file (it does not exist)", os.fspath(path))


def check_readable(path):
    """Raises NoSuchFile (a FileNotFoundError: the path does not exist), IsADirectoryError or
    PermissionError before h5py is asked, so that none of these is reported as a damaged file."""
    if not os.path.exists(path):
        raise _no_such_file(path)
    if os.path.isdir(path):
        raise _IsADirectory(errno.EISDIR, "a directory, not a file", os.fspath(path))
    if not os.access(path, os.R_OK):
        raise _NotReadable(errno.EACCES, "not readable (permission denied)", os.fspath(path))


@contextlib.contextmanager
def open_file(path, check_schema=True):
    """The h5py.File, read-only, after checking that this module reads its schema_version (raw
    access for tests of the layout itself; the readers in files.py are the usual way in)."""
    check_readable(path)
    try:
        handle = h5py.File(path, "r")
    except OSError as error:
        if not os.path.exists(path):  # removed in between
            raise _no_such_file(path) from None
        raise DamagedFile(f"{path}: cannot be read as HDF5 (damaged, truncated or not HDF5: {error})") from None
    with handle:
        if check_schema:
            check_schema_version(path, decode_attributes(handle))
        yield handle


def _natural_key(name):
    """Groups named 0, 1, ..., 10 in numeric order (not 0, 1, 10, 2); other names after, by name."""
    return (0, int(name), "") if re.fullmatch(r"\d+", name) else (1, 0, name)


class Group:
    """One HDF5 group read into memory: `attrs` (dict, text as str), `data` (dataset name -> numpy
    array) and `groups` (subgroup name -> Group, numbered ones in numeric order).
    g["a/b"] reaches datasets and subgroups by path; g.name gives a dataset, else an attribute."""

    def __init__(self, attrs, data, groups, path="/"):
        self.attrs, self.data, self.groups, self.path = attrs, data, groups, path

    def __getitem__(self, key):
        head, _, rest = key.strip("/").partition("/")
        if rest:
            return self.groups[head][rest]
        if head in self.data:
            return self.data[head]
        if head in self.groups:
            return self.groups[head]
        raise KeyError(f"{self.path}: no dataset or group {key!r}")

    def __contains__(self, key):
        try:
            self[key]
        except KeyError:
            return False
        return True

    def __getattr__(self, name):
        if name.startswith("_") or name in ("attrs", "data", "groups", "path"):
            raise AttributeError(name)
        if name in self.data:
            return self.data[name]
        if name in self.attrs:
            return self.attrs[name]
        raise AttributeError(f"{self.path}: no dataset or attribute {name!r}")

    def __repr__(self):
        shapes = ", ".join(f"{k}{list(v.shape)}" for k, v in self.data.items())
        return (f"<{type(self).__name__} {self.path}: {len(self.attrs)} attributes; datasets {shapes or 'none'}; "
                f"groups {list(self.groups) or 'none'}>")


def read_group(obj, path="/"):
    """The whole tree under an h5py group, as Group objects."""
    data, groups = {}, {}
    for name in sorted(obj.keys(), key=_natural_key):
        child = obj[name]
        if isinstance(child, h5py.Dataset):
            value = read_dataset(obj.file.filename, child)
            text = isinstance(value, bytes) or (isinstance(value, np.ndarray) and value.dtype.kind in "SO")
            data[name] = decode(value) if text else value  # text as str (lists of str); numbers as numpy
        else:
            groups[name] = read_group(child, path.rstrip("/") + "/" + name)
    return Group(decode_attributes(obj), data, groups, path)


def walk(path, raw=False, check_schema=True):
    """Every object of a file in a fixed order: yields (object path, attributes, dataset value or None),
    the root first as "/". Attributes are decoded (text as str) unless raw=True, which gives h5py's
    own values for bit-for-bit comparisons."""
    with open_file(path, check_schema) as handle:
        attributes = (lambda o: dict(o.attrs)) if raw else decode_attributes
        yield "/", attributes(handle), None
        names = []
        handle.visit(names.append)
        for name in names:
            obj = handle[name]
            value = read_dataset(path, obj) if isinstance(obj, h5py.Dataset) else None
            yield "/" + name, attributes(obj), value
