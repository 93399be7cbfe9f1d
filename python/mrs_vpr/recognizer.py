"""PlaceRecognizer: the core's recognizer with its parameters as keywords."""

import os

from mrs_vpr import _bindings
from mrs_vpr.parameters import exact_names


class PlaceRecognizer(_bindings.PlaceRecognizer):
    """Sequence-based place recognition over a map of frames.

        recognizer = PlaceRecognizer(descriptor_type="thumbnail", sequence_length=10, tau=2.0)

    Every parameter of the core is a keyword (mrs_vpr.parameter_reference() lists them); the rest keep
    their documented defaults. An unknown parameter or a value out of range raises ValueError with the
    core's message. Images are NumPy arrays: H x W grey or H x W x 3 BGR, uint8 or uint16 (or
    RGB with channel_order="rgb"), strided or not. Stamps are seconds (float), kept to the nearest
    nanosecond. The map keeps a frame only once its view has changed by min_appearance_change (0.4 of
    the difference between unrelated views; 0 keeps every frame), as the node does; match() keyframes
    its test sequence the same way. Every method may be called from any thread; the core runs without
    the GIL.
    """

    def __init__(self, **parameters):
        super().__init__(exact_names(parameters))

    @classmethod
    def from_map(cls, path, **parameters):
        """A recognizer holding the map database `path`, with the front end it was written with unless
        `parameters` choose another (which the map then refuses, naming both), and keyframing frames at
        the appearance change the map's were kept at, where it records one, unless `parameters` choose."""
        chosen = exact_names(parameters, whole=False)
        settings = _bindings.map_front_end(os.fspath(path))
        if chosen.get("descriptor/type", settings["descriptor/type"]) != settings["descriptor/type"]:
            settings = {}  # Another front end, as chosen, whose recognizer the map then refuses.
        settings.update(chosen)
        recognizer = cls(**settings)
        recognizer.load(path)
        return recognizer

    @staticmethod
    def check_save_target(path):
        """Raises MapDatabaseError (a ValueError) naming the problem when save(path) would refuse `path`
        (empty, a folder, a file that exists, no such folder, an earlier map's log beside it, a name
        too long), so that a script can check it before its work, as the tools check their outputs."""
        _bindings.check_save_target(os.fspath(path))

    def save(self, path):
        """Writes the map to the new SQLite map database `path` (never overwritten, written aside and
        renamed when complete); returns the frames written. Raises MapDatabaseError (a ValueError)."""
        return super().save(os.fspath(path))

    def load(self, path):
        """Replaces the map by the map database `path`, checked first (integrity, front end, size);
        returns its frames. On any error the map stays as it was. Raises MapDatabaseError (a
        ValueError)."""
        return super().load(os.fspath(path))

    def __repr__(self):
        return "PlaceRecognizer(frames=%d, front_end=%r, default_method=%r)" % (
            len(self), self.front_end, self.parameters["default_method"])
