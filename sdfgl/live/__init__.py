"""Live control: drive a scene's live parameters from MIDI controllers and OSC, from Python and the viewer.

Needs the optional extra ``sdfgl[live]`` (mido, python-rtmidi, python-osc) for the inputs;
bindings, their files and the message handlers work without it.
"""
from .bindings import Binding, bindings_from_dict, bindings_to_dict, load_bindings, save_bindings
from .control import LiveControl, live_control
from .errors import LiveBindingError, LiveInputError
from .osc import send as send_osc

__all__ = ["Binding", "LiveControl", "LiveBindingError", "LiveInputError", "live_control", "load_bindings",
           "save_bindings", "bindings_from_dict", "bindings_to_dict", "send_osc"]
