"""The core works without the GIL: Python threads go on while a query runs."""

import threading
import time

import mrs_vpr


def test_frames_are_added_from_another_thread_while_a_query_holds_the_map(route):
    # A frame added while a query holds the map waits in the pending buffer. Seeing one there proves
    # that this thread ran Python while the query ran: with the GIL held, no frame could arrive then.
    # Every frame offered must be kept for the count below (min_appearance_change=0): the map cycles over
    # the route's frames, and whether a view is new enough is not what this test is about.
    recognizer = mrs_vpr.PlaceRecognizer(descriptor_type="thumbnail", velocity_step=0.005, max_pending_frames=1000000,
                                         min_appearance_change=0)
    for _ in range(4):
        recognizer.add_frames(route["reference"])
    test = route["query"][:300]
    started = threading.Event()
    answers = []

    def query():
        started.set()
        answers.append(recognizer.match(test, method="seqslam"))

    worker = threading.Thread(target=query)
    worker.start()
    started.wait()
    most_pending = 0
    added = 0
    while worker.is_alive():
        assert recognizer.add_frame(route["query"][added % 400])
        added += 1
        most_pending = max(most_pending, recognizer.pending_frames)
        time.sleep(0.001)
    worker.join()
    assert len(answers) == 1
    assert most_pending > 0
    # Every frame is kept: in the map, or still pending when it came as the query let go of the map;
    # the next query moves those in.
    assert len(recognizer) + recognizer.pending_frames == 2400 + added
    recognizer.match(test[:20])
    assert recognizer.pending_frames == 0
    assert len(recognizer) == 2400 + added


def test_frames_offered_while_another_thread_loads_a_map_are_numbered_in_the_map_they_join(route, tmp_path):
    # Numbered in the old map's count but joining the new one, a frame would break the increasing
    # numbers by which mrs_vpr_eval reads a saved map's ground truth.
    saved = mrs_vpr.PlaceRecognizer(descriptor_type="thumbnail", min_appearance_change=0)
    saved.add_frames(route["reference"][:300])
    path = tmp_path / "map.db"
    saved.save(path)
    for attempt in range(5):
        recognizer = mrs_vpr.PlaceRecognizer(descriptor_type="thumbnail", min_appearance_change=0)
        stop = threading.Event()

        def camera():
            offered = 0
            while not stop.is_set():
                recognizer.add_frame(route["query"][offered % 400])
                offered += 1

        worker = threading.Thread(target=camera)
        worker.start()
        time.sleep(0.05 * attempt)
        recognizer.load(str(path))
        time.sleep(0.02)
        stop.set()
        worker.join()
        numbers = [recognizer.frame_number(index) for index in range(len(recognizer))]
        assert numbers[:300] == list(range(300))
        assert all(later > earlier for earlier, later in zip(numbers, numbers[1:])), numbers[295:310]
