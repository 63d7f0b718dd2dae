"""An inline fixture recognised from its text.

A daemon keeps the text of a long inline fixture (4096 bytes on) and, when a
later line holds the same bytes at params.fixture, uses the fixture made from
it without reading the object again (proto/wp_rpc.c, recognise_fixture).
Nothing but the cost may change: every line below is sent to a daemon that
has kept the text and to a fresh one, and the two answers must be the same,
byte for byte.  The lines are the ones a careless or hostile client would
write around a kept text: a malformed rest, the text inside a string, a
duplicate member, the text with a byte changed, batches, escaped names.
The primed daemon's debug log says which lines it recognised, so the test
also knows the fast way was taken where it should be, and only there.
"""
import json
import math

import pytest

RECOGNISED = "recognised from its inline text"


def long_fixture(bump=0.2, n=300):
    """A 4 x 2 plate whose top is a bow of n vertices (about 12 kB of text),
    against three fixels as in 3-2-1."""
    top = [[4 - 4 * i / (n - 1), 2 + bump * math.sin(math.pi * i / (n - 1))] for i in range(n)]
    return {
        "body": {"mass": 1.0, "shape": {"type": "polygon", "vertices": [[0, 0], [4, 0]] + top}},
        "friction": {"static": 0.3},
        "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}],
    }


def text(value):
    return json.dumps(value, separators=(",", ":"))


FIXTURE = text(long_fixture())


def request(method, params_text, id=1, head='"jsonrpc":"2.0","id":%d,"method":"%s",'):
    return '{' + head % (id, method) + '"params":' + params_text + '}'


def lines():
    """(name, line, recognised?) -- recognised: the primed daemon takes the
    fast way for it."""
    classify = '{"fixture":%s,"wrenches":[[0,1,0.1],[1,1,0],[-0.2,1,0]]}' % FIXTURE
    moved = text(long_fixture(bump=0.2000001))
    assert moved != FIXTURE
    return [
        ("the same line", request("wrench.classify", classify), True),
        ("other wrenches", request("wrench.classify",
                                   '{"fixture":%s,"wrenches":[[0.3,1,-0.4]],"sets":["both"]}'
                                   % FIXTURE, id=2), True),
        ("another method", request("push.regions", '{"fixture":%s,"set":"both"}' % FIXTURE, id=3),
         True),
        ("params before method", '{"params":%s,"jsonrpc":"2.0","method":"wrench.classify","id":4}'
         % classify, True),
        ("white space around", request("wrench.classify",
                                       '{ "fixture" :  %s , "wrenches":[[0,1,0]]}' % FIXTURE,
                                       id=5), True),
        ("a malformed rest", request("wrench.classify",
                                     '{"fixture":%s,"wrenches":[[0,1,' % FIXTURE, id=6)[:-1],
         True),
        ("garbage after the object", request("wrench.classify",
                                             '{"fixture":%s}},"wrenches":[[0,1,0]]}' % FIXTURE,
                                             id=7), True),
        ("an unknown member after it", request("wrench.classify",
                                               '{"fixture":%s,"wrenches":[[0,1,0]],"colour":1}'
                                               % FIXTURE, id=8), True),
        ("a second fixture member", request("wrench.classify",
                                            '{"fixture":%s,"wrenches":[[0,1,0]],"fixture":"x"}'
                                            % FIXTURE, id=9), True),
        ("the same member escaped before it",
         request("wrench.classify", '{"fi\\u0078ture":"%s","fixture":%s,"wrenches":[[0,1,0]]}'
                 % ("0" * 32, FIXTURE), id=10), True),
        ("a byte changed", request("wrench.classify",
                                   '{"fixture":%s,"wrenches":[[0,1,0.1]]}' % moved, id=11), False),
        ("the text inside a string", request("wrench.classify",
                                             '{"fixture":%s,"wrenches":[[0,1,0]]}'
                                             % json.dumps(FIXTURE), id=12), False),
        ("the method escaped", request("wrench.cl\\u0061ssify", classify, id=13), False),
        ("a batch", "[%s,%s]" % (request("wrench.classify", classify, id=14),
                                 request("plan.get", '{"fixture":%s}' % FIXTURE, id=15)), False),
        ("a method that stores", request("fixture.put", '{"fixture":%s}' % FIXTURE, id=16), False),
        ("a method with no fixture", request("fixture.get", '{"id":%s}' % FIXTURE, id=17), False),
        ("the object cut short", request("wrench.classify",
                                         '{"fixture":%s' % FIXTURE[:-1], id=18)[:-1], False),
        ("params escaped before it",
         '{"jsonrpc":"2.0","id":19,"method":"wrench.classify","par\\u0061ms":{},"params":%s}'
         % classify, True),
        ("a rest nested too deep", request("wrench.classify",
                                           '{"fixture":%s,"wrenches":%s}'
                                           % (FIXTURE, "[" * 200 + "]" * 200), id=20), True),
    ]


def answer(client, line):
    client.send_line(line)
    return client.read_line(timeout=60)


def test_a_kept_text_answers_as_a_fresh_daemon_would(harness):
    primed = harness.start("--log-level", "debug")
    fresh = harness.start(socket_path=harness.path("fresh.sock"))
    p = primed.client()
    prime = request("wrench.classify", '{"fixture":%s,"wrenches":[[0,1,0]]}' % FIXTURE, id=99)
    assert len(FIXTURE) > 4096
    first = answer(p, prime)
    assert b'"result"' in first, first[:300]
    assert RECOGNISED not in primed.stderr()
    recognised = 0
    for name, line, fast in lines():
        f = fresh.client()
        got, want = answer(p, line), answer(f, line)
        f.close()
        assert got == want, "%s: %s\n  against %s" % (name, got[:300], want[:300])
        count = primed.stderr().count(RECOGNISED)
        assert count == recognised + fast, "%s: recognised %d times, expected %d" % (
            name, count - recognised, int(fast))
        recognised = count
    assert recognised == sum(fast for _, _, fast in lines())


def test_a_short_fixture_text_is_not_kept(harness):
    d = harness.start("--log-level", "debug")
    c = d.client()
    small = text({"body": {"mass": 1.0, "shape": {"type": "polygon",
                                                   "vertices": [[0, 0], [4, 0], [4, 2], [0, 2]]}},
                  "friction": {"static": 0.3},
                  "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}]})
    # Long lines (the wrenches make them so) whose fixture is short: read
    # the ordinary way every time (the written key finds it again).
    wrenches = text([[0, 1, 0.001 * i] for i in range(400)])
    line = request("wrench.classify", '{"fixture":%s,"wrenches":%s}' % (small, wrenches))
    assert len(line) > 4096
    a, b = answer(c, line), answer(c, line)
    assert a == b and b'"result"' in a
    assert RECOGNISED not in d.stderr()


@pytest.mark.parametrize("cache_mb", ["1"])
def test_an_evicted_text_is_read_again(harness, cache_mb):
    """With a cache too small for two of them, the texts of fixtures pushed
    out go with them: the line is then read the ordinary way, and answers
    the same."""
    d = harness.start("--log-level", "debug", "--cache-mb", cache_mb)
    c = d.client()
    texts = [text(long_fixture(bump=0.1 + 0.01 * k, n=300)) for k in range(40)]
    lines = [request("wrench.classify", '{"fixture":%s,"wrenches":[[0,1,0]]}' % t, id=k)
             for k, t in enumerate(texts)]
    first = [answer(c, line) for line in lines]
    again = [answer(c, line) for line in lines]
    assert first == again
    log = d.stderr()
    # Pushed out and read again: fewer recognised than asked again.
    assert "evicting" in log, log[-2000:]
    assert log.count(RECOGNISED) < len(lines), log.count(RECOGNISED)
    status = c.result("server.status", {})
    assert status["cache_bytes"] <= status["cache_limit_bytes"], status


def test_a_sequence_answers_alike(harness):
    """Lines whose answers depend on what came before: a notification (no
    answer, then the next line's), and a stored fixture asked inline, then
    deleted, then asked inline again.  The same sequence to a daemon that
    keeps the text, and to one whose lines name the method with an escape,
    which no text is recognised in (method_as_written), so that every
    fixture in them is parsed."""
    primed = harness.start("--log-level", "debug")
    fresh = harness.start("--log-level", "debug", socket_path=harness.path("fresh.sock"))
    put = request("fixture.put", '{"fixture":%s}' % FIXTURE, id=1)
    inline = request("wrench.classify", '{"fixture":%s,"wrenches":[[0,1,0]]}' % FIXTURE, id=2)
    notification = '{"jsonrpc":"2.0","method":"wrench.classify","params":{"fixture":%s,' \
                   '"wrenches":[[0,1,0]]}}' % FIXTURE
    answers = {}
    for name, daemon in (("primed", primed), ("fresh", fresh)):
        def spelt(line):
            return line if name == "primed" else line.replace('"wrench.classify"',
                                                              '"wrench.cl\\u0061ssify"')
        c = daemon.client()
        got = [answer(c, put), answer(c, spelt(inline))]
        c.send_line(spelt(notification))
        got.append(answer(c, spelt(inline)))
        stored_id = json.loads(got[0])["result"]["id"]
        got.append(answer(c, request("fixture.delete", '{"id":"%s"}' % stored_id, id=3)))
        got.append(answer(c, spelt(inline)))
        got.append(answer(c, spelt(inline)))
        answers[name] = got
        c.close()
    assert answers["primed"] == answers["fresh"]
    assert b'"result"' in answers["primed"][3], answers["primed"][3]  # deleted
    assert fresh.stderr().count(RECOGNISED) == 0
    assert primed.stderr().count(RECOGNISED) >= 3
