"""Presenting a plan: the automaton as a picture and the self-contained HTML report.

:func:`write_html_report` writes one HTML file per plan (floors, path, mission, automaton, iterations)
that opens offline; :func:`write_automaton` writes the mission automaton as DOT and SVG. The floor
pictures themselves are :func:`sgplan.scene.draw.draw_building`.
"""

from sgplan.report.automaton import automaton_svg, write_automaton
from sgplan.report.html import report_html, write_html_report

__all__ = ["automaton_svg", "report_html", "write_automaton", "write_html_report"]
