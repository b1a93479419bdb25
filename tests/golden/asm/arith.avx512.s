; inputs finite with |x| <= 65536 (other batches run the general code)
; 8 points per iteration (ymm registers)
L0:
     0    push rbx
     1    push rbp
     2    push r12
     4    push r13
     6    push r14
     8    push r15
     a    mov rbp, rsp
     d    sub rsp, 776
    14    and rsp, -32
    18    mov rbx, rdi
    1b    mov r12, rsi
    1e    mov r15, r8
    21    lea r13, [rdx+rdx*2]
    25    add r13, rdx
    28    lea r14, [rcx+rcx*2]
    2c    add r14, rcx
L2:
    2f    cmp r13, r14
    32    jae L3
L4:
    38    mov rax, [rbx]
    3b    vmovups ymm2, [rax+r13*1]
    41    mov rax, [rbx+8]
    45    vmovups ymm3, [rax+r13*1]
    4b    mov rax, [rbx+16]
    4f    vmovups ymm4, [rax+r13*1]
    55    vminps ymm3, ymm3, ymm2
    59    vmulps ymm4, ymm4, ymm4
    5d    vaddps ymm4, ymm4, [rip+L6]
    65    vsqrtps ymm2, ymm4
    69    vsubps ymm3, ymm3, ymm2
    6d    mov rax, [r12]
    71    vmovups [rax+r13*1], ymm3
L5:
    77    add r13, 32
    7b    jmp L2
L3:
    80    mov rax, 0x0
L1:
    85    mov rsp, rbp
    88    pop r15
    8a    pop r14
    8c    pop r13
    8e    pop r12
    90    pop rbp
    91    pop rbx
    92    vzeroupper
    95    ret
L6:
    a0    .float 1, 1, 1, 1, 1, 1, 1, 1
