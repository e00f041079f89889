# Empty dependencies file for springlab_core.
# This may be replaced when dependencies are built.
