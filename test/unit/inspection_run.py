"""A recorded inspection run for the inspection tests: findings at known
places on inspection_network_90, each with a front and a rear frame."""
import math

from pirate.inspection import findings as fd
from pirate.inspection import frames, store
from pirate.world import network

MAP = 'inspection_network_90'
#: (kind, note, along the map m, camera pan rad, tilt rad, roll rad, frame colour)
MARKED = [
    ('corrosion', 'rust patch on the crown', 3.100, 0.0, 0.6, math.pi / 2, (200, 90, 20)),
    ('leak', 'hissing crack', 1.000, 0.7, 0.0, math.pi / 2, (20, 120, 220)),
    ('deposit', 'silt at the invert', 2.100, 0.0, -0.6, math.pi / 2, (120, 120, 120)),
]
UNCERTAINTY_M = 0.16


def frame(colour, width=32, height=24):
    """PNG bytes of a plain frame of ``colour`` (rgb8)."""
    return frames.png_of(width, height, 'rgb8', width * 3, bytes(colour) * (width * height))


def record(folder, marked=MARKED):
    """Write a run at ``folder`` with ``marked``; the pipe map used."""
    pipe_map = network.load(network.world_path(MAP))
    launch_m = pipe_map.points['launch_pit']
    run = store.RunStore(folder, {'run': 'test run', 'map': MAP, 'launch_pit_mm': launch_m * 1000})
    for kind, note, along_m, pan, tilt, roll, colour in marked:
        number = run.next_number()
        saved = {camera: run.save_frame(number, camera, frame(colour)) for camera in ('front', 'rear')}
        run.append({'number': number, 'kind': kind, 'note': note, 'stamp_s': 10.0 * number,
                    'wall_time': '2026-11-27T18:00:%02dZ' % number, 'frames': saved,
                    'position': fd.position_on_map(pipe_map, along_m, launch_m, UNCERTAINTY_M, pan, tilt, roll)})
    return pipe_map
