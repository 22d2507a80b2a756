"""Robot state: Small State -> SI units (assembler), its ROS node, and the feed the sequencer reads."""
