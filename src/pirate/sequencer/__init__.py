"""The Sequential layer (report 3.2): Pirate Server, motion primitives, guards and the PABs."""
