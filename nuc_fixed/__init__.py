"""Bit-accurate fixed-point golden model of the irnuc NUC + DPC pipeline."""

from nuc_fixed.config import PipelineConfig, load_pipeline, pipeline_names

__all__ = ["PipelineConfig", "load_pipeline", "pipeline_names"]
