"""Pictures shared by the jobs (matplotlib, Agg): ``scenes`` draws scenes, parts, trees and
paths and saves figures; ``atlas`` builds and draws the corners of the Table 2 box."""
