"""Every public module, function, class, method and property of torsio has a docstring."""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import torsio


def public_objects():
    for info in pkgutil.walk_packages(torsio.__path__, "torsio."):
        if info.name.endswith("__main__"):
            continue
        module = importlib.import_module(info.name)
        yield info.name, module
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
                continue
            if inspect.isfunction(obj) or inspect.isclass(obj):
                yield f"{info.name}.{name}", obj
            if inspect.isclass(obj):
                for member_name, member in vars(obj).items():
                    if member_name.startswith("_"):
                        continue
                    target = member.fget if isinstance(member, property) else member
                    if inspect.isfunction(target) or isinstance(member, property):
                        yield f"{info.name}.{name}.{member_name}", target


def test_every_public_object_has_a_docstring():
    missing = [name for name, obj in public_objects() if not inspect.getdoc(obj)]
    assert missing == []
