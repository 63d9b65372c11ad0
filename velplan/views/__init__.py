"""Views: pure functions from results (kinematics, plans, tables, diagrams, forces, dynamics)
and a drawing scale to shapes in view millimetres (`velplan.views.base.View`).

A view never solves or evaluates anything: it draws what a `velplan.study.Study` computed.
"""
