"""The lab: a real experiment's recording becomes a fitted model.

Between the simulation and the outputs: the lab reads measured data (a video tracked with
OpenCV, a plain or Tracker CSV) and fits the model to it by least squares on the exact
simulated motion. It computes, so it sits below the outputs, which only render its results.
"""
