"""The package imports from the devel space beside the node's messages and services."""

import subprocess
import sys

import mrs_vpr


def test_the_recognizer_and_the_messages_import_side_by_side():
    import mrs_vpr.msg
    import mrs_vpr.srv

    assert mrs_vpr.msg.LoopClosure.__name__ == "LoopClosure"
    assert mrs_vpr.srv.QuerySequence.__name__ == "QuerySequence"
    assert callable(mrs_vpr.PlaceRecognizer)


def test_a_rejected_closure_is_sent_as_rosservice_would_send_it():
    # `rosservice call ~reject_closure` builds this request from the closure's two fields.
    from io import BytesIO

    import genpy
    import mrs_vpr.srv

    request = mrs_vpr.srv.RejectClosureRequest(
        localised_keyframe_stamp=genpy.Time(1700003614, 350000000), reference_index=277)
    buffer = BytesIO()
    request.serialize(buffer)
    received = mrs_vpr.srv.RejectClosureRequest().deserialize(buffer.getvalue())
    assert (received.localised_keyframe_stamp.secs, received.localised_keyframe_stamp.nsecs) == (1700003614, 350000000)
    assert received.reference_index == 277


def test_importing_the_messages_does_not_load_the_recognizer():
    # A ROS program that only talks to the node must not pay for the core's libraries.
    code = "import sys, mrs_vpr.msg, mrs_vpr.srv; print('mrs_vpr._bindings' in sys.modules)"
    output = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout
    assert output.strip() == "False"


def test_an_unknown_name_is_an_attribute_error():
    try:
        mrs_vpr.NoSuchThing
    except AttributeError as error:
        assert "NoSuchThing" in str(error)
    else:
        raise AssertionError("no AttributeError")
