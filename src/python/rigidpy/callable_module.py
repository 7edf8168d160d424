"""`rigidpy.fragility(...)` and `rigidpy.hazard(...)` are the API's functions (fits_data), and
`rigidpy.fragility` and `rigidpy.hazard` are also modules of the package (the commands, the hazard
curves) that other modules import by those names. A package attribute can be only one of the two,
and Python sets it to the module whenever the module is first imported; so each of these two
modules is made callable, calling the API's function of its name."""
import importlib
import sys
import types


def call_through(module_name, function_module, function_name):
    """Makes sys.modules[module_name] callable as `function_module.function_name` (imported on
    the first call, so that neither module imports the other at load time)."""

    class CallableModule(types.ModuleType):
        def __call__(self, *args, **kwargs):
            function = getattr(importlib.import_module(function_module), function_name)
            return function(*args, **kwargs)

    sys.modules[module_name].__class__ = CallableModule
