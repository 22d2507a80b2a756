"""Camera frames as PNG: pure (Pillow), from the fields of a sensor_msgs/Image."""
import io

from PIL import Image

#: sensor_msgs/Image encodings taken: (Pillow mode of the raw bytes, bytes per pixel).
ENCODINGS = {'rgb8': ('RGB', 3), 'bgr8': ('BGR', 3), 'rgba8': ('RGBA', 4), 'bgra8': ('BGRA', 4), 'mono8': ('L', 1)}


class FrameError(ValueError):
    """A frame that cannot be turned into a PNG."""


def png_of(width, height, encoding, step, data):
    """PNG bytes of one image (``step``: bytes per row, as sensor_msgs/Image)."""
    if encoding not in ENCODINGS:
        raise FrameError('encoding %r is not one of %s' % (encoding, ', '.join(sorted(ENCODINGS))))
    mode, size = ENCODINGS[encoding]
    if width <= 0 or height <= 0 or step < width * size or len(data) < step * height:
        raise FrameError('a %dx%d %s image needs %d bytes in rows of %d, got %d in rows of %d'
                         % (width, height, encoding, width * size * height, width * size, len(data), step))
    rows = b''.join(bytes(data[r * step:r * step + width * size]) for r in range(height))
    if mode in ('BGR', 'BGRA'):
        image = Image.frombytes('RGBA' if mode == 'BGRA' else 'RGB', (width, height), rows,
                                'raw', mode)
    else:
        image = Image.frombytes(mode, (width, height), rows)
    out = io.BytesIO()
    image.save(out, format='PNG')
    return out.getvalue()
