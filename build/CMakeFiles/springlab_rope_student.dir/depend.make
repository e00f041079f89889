# Empty dependencies file for springlab_rope_student.
# This may be replaced when dependencies are built.
