"""The pirate_manager process (report Fig 4.1): the Pirate Server behind its
action server, the Mapper of the operator panel and the panel's action
client, composed around one Setpoint / Control / Limit. Above both
:mod:`pirate.sequencer` and :mod:`pirate.panel`, which import neither it nor
each other's ROS edges."""
