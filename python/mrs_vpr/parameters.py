"""The core's parameters as Python keywords.

Every parameter of the core's tables (mrs_vpr/parameters.hpp) is accepted by its exact name
("sequence/sequence_length", valid as **{...}) and, where no other parameter claims the same word, by
its name without the group ("sequence_length", "tau", "hog_cell_size") or with the group joined by an
underscore ("descriptor_type", "mrs_seed"). A parameter added to the tables is accepted without a
change here.
"""

import difflib

from mrs_vpr import _bindings


def _candidates(name):
    """The keywords `name` may be given by, the exact name first."""
    parts = name.split("/")
    if len(parts) == 1:
        return [name]
    group, short = parts[0], "_".join(parts[1:])
    candidates = [name, short]
    if not short.startswith(group + "_"):
        candidates.append(group + "_" + short)
    return candidates


def _keyword_table(reference):
    """Keyword -> exact name, for every keyword that names one parameter only."""
    claims = {}
    for row in reference:
        for keyword in _candidates(row["name"]):
            claims.setdefault(keyword, set()).add(row["name"])
    return {keyword: names.pop() for keyword, names in claims.items() if len(names) == 1}


# Read once, when the module is imported: the core's tables do not change.
_REFERENCE = _bindings.parameter_reference()
_KEYWORDS = _keyword_table(_REFERENCE)
_DEFAULTS = {row["name"]: row["default"] for row in _REFERENCE}
#: Exact name -> the front end it belongs to, for the parameters of one front end only.
_FRONT_END_OF = {row["name"]: row["front_end"] for row in _REFERENCE if row["front_end"]}


def parameter_reference():
    """Every parameter as a dict: name, keywords, type, default, allowed, meaning."""
    rows = _bindings.parameter_reference()
    for row in rows:
        row["keywords"] = [k for k in _candidates(row["name"]) if _KEYWORDS.get(k) == row["name"]]
    return rows


def exact_names(parameters, whole=True):
    """`parameters` (keyword -> value) by exact name. Raises ValueError for an unknown keyword, a
    parameter given twice or, when they are the `whole` set, a parameter of a front end other than the
    one they choose set to other than its default, which would change nothing (at its default it is
    let through: PlaceRecognizer(**other.parameters) copies a recognizer's settings)."""
    resolved = {}
    given_as = {}
    for keyword, value in parameters.items():
        name = _KEYWORDS.get(keyword)
        if name is None:
            close = difflib.get_close_matches(keyword, list(_KEYWORDS), n=1)
            hint = " (did you mean '%s'?)" % close[0] if close else ""
            raise ValueError("unknown parameter '%s'%s; mrs_vpr.parameter_reference() lists every parameter"
                             % (keyword, hint))
        if name in resolved:
            raise ValueError("%s is given twice, as '%s' and '%s'" % (name, given_as[name], keyword))
        resolved[name] = value
        given_as[name] = keyword
    front_end = resolved.get("descriptor/type", _DEFAULTS["descriptor/type"])
    if whole and front_end in _FRONT_END_OF.values():
        for name, keyword in given_as.items():
            owner = _FRONT_END_OF.get(name, front_end)
            if owner != front_end and resolved[name] != _DEFAULTS[name]:
                raise ValueError("'%s' is a parameter of the %s front end, and the front end is %s (add "
                                 "descriptor_type=%r)" % (keyword, owner, front_end, owner))
    return resolved
