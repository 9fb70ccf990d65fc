"""Comparing a result's to_dict() with the CLI's --json document: the same keys, lists and strings everywhere, numbers
equal to a relative 1e-12 (the library is the same; Eigen may sum in another order where memory is aligned
differently, which moves the last bit of a few results, e.g. an event's tool force)."""
import math


def assert_same_document(actual, expected, path="", rel=1e-12):
    if isinstance(expected, dict):
        assert isinstance(actual, dict) and actual.keys() == expected.keys(), f"{path}: keys differ"
        for key in expected:
            assert_same_document(actual[key], expected[key], f"{path}.{key}", rel)
    elif isinstance(expected, list):
        assert isinstance(actual, list) and len(actual) == len(expected), f"{path}: lengths differ"
        for index, (a, e) in enumerate(zip(actual, expected)):
            assert_same_document(a, e, f"{path}[{index}]", rel)
    elif isinstance(expected, float) and not isinstance(actual, bool) and isinstance(actual, (int, float)):
        assert math.isclose(actual, expected, rel_tol=rel, abs_tol=1e-300), f"{path}: {actual} != {expected}"
    else:
        assert type(actual) is type(expected) and actual == expected, f"{path}: {actual!r} != {expected!r}"
