"""Sequence-based visual place recognition (SeqSLAM and MRS-VPR) for Python and NumPy.

    import mrs_vpr

    recognizer = mrs_vpr.PlaceRecognizer(descriptor_type="thumbnail", sequence_length=10)
    recognizer.add_frames(map_images)  # N x H x W grey or N x H x W x 3 BGR, uint8; keeps keyframes
    answer = recognizer.match(query_images[-50:])  # where do the newest 50 frames lie in the map?
    if answer.accepted:
        print(answer.reference_index, answer.confidence)

The node's ROS messages and services are the submodules mrs_vpr.msg and mrs_vpr.srv. Importing them
does not load the recognizer: the names below are loaded on first use.
"""

# Name -> module that defines it, imported on first access (PEP 562), so that a ROS program that
# imports mrs_vpr.msg loads neither the core's library nor NumPy.
_LAZY_NAMES = {
    "PlaceRecognizer": "mrs_vpr.recognizer",
    "parameter_reference": "mrs_vpr.parameters",
    "Answer": "mrs_vpr._bindings",
    "Match": "mrs_vpr._bindings",
    "MapDatabaseError": "mrs_vpr._bindings",
    "synthetic_route": "mrs_vpr._bindings",
    "evaluate": "mrs_vpr.evaluation",
    "image_files": "mrs_vpr._bindings",
    "Evaluation": "mrs_vpr.evaluation",
}

__all__ = sorted(_LAZY_NAMES)


def __getattr__(name):
    module_name = _LAZY_NAMES.get(name)
    if module_name is None:
        raise AttributeError("module 'mrs_vpr' has no attribute '%s'" % name)
    import importlib

    value = getattr(importlib.import_module(module_name), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY_NAMES))
