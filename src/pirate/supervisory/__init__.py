"""The Supervisory layer (report 3.2): missions made of PABs."""
