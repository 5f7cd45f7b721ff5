"""Copy one node (a dataset, or a group with everything below it) between projects."""

from __future__ import annotations

from hydrosync_core.errors import InputError


def copy_subtree(src, dst, path: str) -> None:
    """Replace *path* in project *dst* by *src*'s node there.

    A dataset is copied with its attributes; a group with its attributes, datasets and
    sub-groups. Used to move data read into a scratch project (so a bad file never
    touches the real one) into the user's project.
    """
    path = path.strip("/")
    try:
        data = src.get(path)
    except InputError:  # a group: copy its attributes and everything below it
        dst.delete(path)
        dst.ensure_group(path)
        dst.set_attrs(path, **src.attrs(path))
        for info in src.walk(path):
            if info.kind == "group":
                dst.ensure_group(info.path)
                dst.set_attrs(info.path, **info.attrs)
            else:
                dst.put(info.path, src.get(info.path), attrs=info.attrs)
    else:
        dst.put(path, data, attrs=src.attrs(path))
